// SPDX-License-Identifier: MIT
// Builds the page into one folder of static files (CMake passes --outDir), served by `sewerplan serve`.
import { defineConfig } from 'vite';

export default defineConfig({
  base: './',
  build: { emptyOutDir: true, chunkSizeWarningLimit: 2000 },
});
