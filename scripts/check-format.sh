#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Fails if any C++ file differs from what clang-format (the repo's .clang-format) would write.
# Fix with: git ls-files '*.h' '*.cc' | xargs clang-format -i
set -euo pipefail
cd "$(dirname "$0")/.."
git ls-files -z '*.h' '*.cc' | xargs -0 -r clang-format --dry-run --Werror
echo "clang-format: clean"
