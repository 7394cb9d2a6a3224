// SPDX-License-Identifier: MIT
// SvgCanvas: a Canvas (canvas.h) written as SVG text, with fixed number formats (one decimal), so
// that the same scene gives the same bytes. Tags become ids, classes and <title> tooltips.
#pragma once

#include <sstream>
#include <string>

#include "sewerplan/render/canvas.h"

namespace sewerplan::render {

class SvgCanvas final : public Canvas {
 public:
  Result<void> begin(double width, double height) override;
  bool keeps_tags() const override { return true; }
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
  void open(std::string_view element, const Tag& tag);
  void paint(const Paint& p);
  void close(std::string_view element, const Tag& tag);

  std::ostringstream out_;
  int clip_count_ = 0;
};

}  // namespace sewerplan::render
