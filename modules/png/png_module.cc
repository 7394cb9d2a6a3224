// SPDX-License-Identifier: MIT
// The PNG module's two exported symbols (sewerplan/modules/png_table.h, module.h): its ABI stamp
// and the table that makes cairo canvases, built into sewerplan_png.so with everything else
// hidden.
#include <memory>
#include <string>

#include "sewerplan/modules/png_table.h"

#include "png_canvas.h"

namespace sewerplan::modules {
namespace {

std::unique_ptr<render::Canvas> make_png_canvas() { return std::make_unique<render::PngCanvas>(); }

const PngTable kTable{.make_png_canvas = &make_png_canvas};

}  // namespace
}  // namespace sewerplan::modules

extern "C" __attribute__((visibility("default"))) const char* sewerplan_png_module_stamp() {
  static const std::string stamp = sewerplan::modules::png_stamp();
  return stamp.c_str();
}

extern "C" __attribute__((visibility("default"))) const void* sewerplan_png_module() {
  return &sewerplan::modules::kTable;
}
