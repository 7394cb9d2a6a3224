// SPDX-License-Identifier: MIT
// A map picture as PNG, drawn by cairo in the PNG module (png_table.h), loaded on the first call:
// the one place a program reaches cairo. render draws on any Canvas (sewerplan/render/
// map_picture.h: draw_map) and never loads or links cairo.
//
//   Result<std::string> png = render_map_png({.map = &map, .mission = &mission});  // bytes
//
// Thread safety: load_module's (any thread); each call draws on a canvas of its own.
#pragma once

#include <string>

#include "sewerplan/core/result.h"
#include "sewerplan/render/map_picture.h"

namespace sewerplan::modules {

// PNG bytes: an error (kInvalidArgument) for a picture too large for one; kUnsupportedFormat,
// naming the module and why ("a PNG picture needs cairo, but ..."), when the module is missing or
// of another build.
Result<std::string> render_map_png(const render::RenderInput& input);

}  // namespace sewerplan::modules
