// SPDX-License-Identifier: MIT
// The PNG module's two exported symbols (sewerplan/render/png_module.h, sewerplan/core/module.h):
// its ABI stamp and the table that makes cairo canvases, built into sewerplan_png.so with
// everything else hidden.
#include "sewerplan/render/png_module.h"

#include <memory>
#include <string>

#include "png_canvas.h"

namespace sewerplan::render {
namespace {

std::unique_ptr<Canvas> make_png_canvas() { return std::make_unique<PngCanvas>(); }

const PngModuleTable kTable{.make_png_canvas = &make_png_canvas};

}  // namespace
}  // namespace sewerplan::render

extern "C" __attribute__((visibility("default"))) const char* sewerplan_png_module_stamp() {
  static const std::string stamp = sewerplan::render::png_module_stamp();
  return stamp.c_str();
}

extern "C" __attribute__((visibility("default"))) const void* sewerplan_png_module() {
  return &sewerplan::render::kTable;
}
