// SPDX-License-Identifier: MIT
// The PNG module: the cairo canvas (a Canvas, canvas.h, rasterised by cairo and written as PNG)
// behind one table in a shared module (sewerplan_png.so, modules/png/) that render_map_png (png.h)
// loads with dlopen the first time it draws a PNG. cairo pulls in about thirty shared libraries
// (pixman, fontconfig, freetype, libpng, xcb, X11, ...); linked into a program, every run of it
// paid about 10 ms of CPU for loading and relocating them (docs/benchmarks.md), though only a PNG
// picture uses them. Behind the module only the runs that draw a PNG load them; SVG never does.
//
// A module of sewerplan (module.h), named "png": it exports sewerplan_png_module_stamp, its ABI
// stamp (png_stamp() below as built into it), and sewerplan_png_module, the table. The canvas it
// makes is an object of the module: its virtual functions and its destructor are the module's code,
// and the module is never unloaded.
//
// Thread safety: make_png_canvas may be called from any thread; each canvas is used by one thread
// at a time (canvas.h).
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "sewerplan/core/result.h"
#include "sewerplan/modules/module.h"
#include "sewerplan/render/canvas.h"

namespace sewerplan::modules {

struct PngTable {
  // A new canvas drawn by cairo: begin, draw, then finish() gives the PNG bytes. begin is an error
  // (kInvalidArgument) for a picture over 32,767 pixels a side or 100 million pixels.
  std::unique_ptr<render::Canvas> (*make_png_canvas)();
};

inline constexpr const char* kPngModule = "png";

// This build's ABI stamp for the table: the size of every type crossing it (module.h). The
// canvas's virtual functions cross it too: their layout is
// canvas.h's, which the build id covers.
inline std::string png_stamp() {
  const ModuleType types[] = {
      {"PngTable", sizeof(PngTable)},
      {"Canvas", sizeof(render::Canvas)},
      {"unique_ptr<Canvas>", sizeof(std::unique_ptr<render::Canvas>)},
      {"Result<void>", sizeof(Result<void>)},
      {"Result<string>", sizeof(Result<std::string>)},
      {"Point", sizeof(render::Point)},
      {"Paint", sizeof(render::Paint)},
      {"Tag", sizeof(render::Tag)},
      {"Font", sizeof(render::Font)},
      {"Rect", sizeof(render::Rect)},
      {"span<const Point>", sizeof(std::span<const render::Point>)},
      {"string_view", sizeof(std::string_view)},
  };
  return module_abi_stamp(types);
}

}  // namespace sewerplan::modules
