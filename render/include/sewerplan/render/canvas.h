// SPDX-License-Identifier: MIT
// Canvas: the drawing primitives a map picture is made of, so that one scene (map_picture.h)
// is written once and drawn as SVG or as PNG.
//
// Coordinates are picture pixels, x right and y down. A primitive has a Paint (fill and stroke;
// a colour may be none) and a Tag: the SVG element's id and class and its tooltip, which a
// raster ignores (ask keeps_tags() before building tooltips for 100,000 pipes). Lines and
// polylines have round caps and joins. Groups nest; a group may clip what is drawn in it to a
// rectangle.
//
//   canvas.begin(400, 300);
//   canvas.line({10, 10}, {390, 290}, {.stroke = Colour::rgb(0x6b8fb3), .stroke_width = 2});
//   Result<std::string> picture = canvas.finish();
//
// Two implementations: render's src/svg_canvas.h (text) and the PNG module's png_canvas.h (cairo,
// Debian libcairo2: modules/png/, sewerplan/modules/png_table.h). draw_map (map_picture.h) draws a
// map on any Canvas.
//
// Thread safety: a canvas is used by one thread at a time.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "sewerplan/core/result.h"

namespace sewerplan::render {

struct Point {
  double x = 0;
  double y = 0;
};

struct Colour {
  std::uint32_t value = 0;  // 0xRRGGBB
  bool none = false;
  static constexpr Colour rgb(std::uint32_t v) { return {v, false}; }
  static constexpr Colour transparent() { return {0, true}; }
};

struct Paint {
  Colour fill = Colour::transparent();
  Colour stroke = Colour::transparent();
  double stroke_width = 1;
  double stroke_opacity = 1;
  double dash_on = 0;  // dash pattern in pixels; 0: solid
  double dash_off = 0;
};

struct Tag {
  std::string_view id;
  std::string_view cls;
  std::string_view title;  // tooltip
};

enum class Anchor { kStart, kMiddle };

struct Font {
  double size = 11;
  Colour colour = Colour::rgb(0x000000);
  Anchor anchor = Anchor::kStart;
  bool bold = false;
};

struct Rect {
  double x = 0;
  double y = 0;
  double width = 0;
  double height = 0;
};

class Canvas {
 public:
  virtual ~Canvas() = default;
  // Starts a white picture of this size in pixels; an error when the canvas cannot hold it.
  virtual Result<void> begin(double width, double height) = 0;
  // Whether tags (ids, classes, tooltips) are kept: callers may skip building them otherwise.
  virtual bool keeps_tags() const = 0;
  virtual void begin_group(std::string_view id, const Rect* clip = nullptr) = 0;
  virtual void end_group() = 0;
  virtual void line(Point a, Point b, const Paint& paint, const Tag& tag = {}) = 0;
  virtual void polyline(std::span<const Point> points, const Paint& paint, const Tag& tag = {}) = 0;
  virtual void polygon(std::span<const Point> points, const Paint& paint, const Tag& tag = {}) = 0;
  // Unconnected segments: points[0]-points[1], points[2]-points[3], ... as one shape.
  virtual void segments(std::span<const Point> points, const Paint& paint, const Tag& tag = {}) = 0;
  virtual void circle(Point centre, double r, const Paint& paint, const Tag& tag = {}) = 0;
  virtual void rect(const Rect& r, const Paint& paint, const Tag& tag = {}) = 0;
  virtual void text(Point at, std::string_view text, const Font& font, const Tag& tag = {}) = 0;
  // The finished picture: SVG text, or PNG bytes.
  virtual Result<std::string> finish() = 0;
};

}  // namespace sewerplan::render
