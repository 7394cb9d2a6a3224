// SPDX-License-Identifier: MIT
// PngCanvas: a Canvas (canvas.h) rasterised by cairo (Debian libcairo2) and written as PNG.
//
// Why cairo: it draws exactly the SVG primitives a map picture uses (anti-aliased lines with caps,
// dashes, circles, paths, clipping, text through fontconfig), writes PNG itself, is in Debian 12
// as a small, long-maintained C library (libcairo2, already on most systems through GTK), and
// stays private to the PNG module (sewerplan/modules/png_table.h): no cairo type is in a header,
// and only the runs that draw a PNG load it. Tags are ignored.
#pragma once

#include <memory>
#include <string>

#include "sewerplan/render/canvas.h"

namespace sewerplan::render {

class PngCanvas final : public Canvas {
 public:
  PngCanvas();
  ~PngCanvas() override;
  PngCanvas(const PngCanvas&) = delete;
  PngCanvas& operator=(const PngCanvas&) = delete;

  // An error (kInvalidArgument) for a picture over 32,767 pixels a side or 100 million pixels.
  Result<void> begin(double width, double height) override;
  bool keeps_tags() const override { return false; }
  void begin_group(std::string_view id, const Rect* clip) override;
  void end_group() override;
  void line(Point a, Point b, const Paint& paint, const Tag& tag) override;
  void polyline(std::span<const Point> points, const Paint& paint, const Tag& tag) override;
  void polygon(std::span<const Point> points, const Paint& paint, const Tag& tag) override;
  void segments(std::span<const Point> points, const Paint& paint, const Tag& tag) override;
  void circle(Point centre, double r, const Paint& paint, const Tag& tag) override;
  void rect(const Rect& r, const Paint& paint, const Tag& tag) override;
  void text(Point at, std::string_view text, const Font& font, const Tag& tag) override;
  Result<std::string> finish() override;

 private:
  struct Cairo;
  void draw(const Paint& paint);
  std::unique_ptr<Cairo> cairo_;
};

}  // namespace sewerplan::render
