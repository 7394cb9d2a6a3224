// SPDX-License-Identifier: MIT
// A Canvas as SVG text (svg_canvas.h).
#include "svg_canvas.h"

#include <cstdio>

namespace sewerplan::render {
namespace {

std::string f1(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", v);
  return buffer;
}

std::string colour(Colour c) {
  if (c.none) return "none";
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "#%06x", c.value & 0xffffffU);
  return buffer;
}

std::string escape(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == '&')
      out += "&amp;";
    else if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

}  // namespace

Result<void> SvgCanvas::begin(double width, double height) {
  out_ << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << f1(width) << "\" height=\""
       << f1(height) << "\" viewBox=\"0 0 " << f1(width) << ' ' << f1(height)
       << "\" font-family=\"sans-serif\" font-size=\"11\" stroke-linecap=\"round\" "
          "stroke-linejoin=\"round\">\n"
       << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  return {};
}

void SvgCanvas::begin_group(std::string_view id, const Rect* clip) {
  std::string clip_id;
  if (clip != nullptr) {
    clip_id = std::string(id.empty() ? "clip" : id) + "-area";
    if (clip_count_++ > 0) clip_id += std::to_string(clip_count_);
    out_ << "<clipPath id=\"" << clip_id << "\"><rect x=\"" << f1(clip->x) << "\" y=\""
         << f1(clip->y) << "\" width=\"" << f1(clip->width) << "\" height=\"" << f1(clip->height)
         << "\"/></clipPath>\n";
  }
  out_ << "<g";
  if (!id.empty()) out_ << " id=\"" << escape(id) << '"';
  if (!clip_id.empty()) out_ << " clip-path=\"url(#" << clip_id << ")\"";
  out_ << ">\n";
}

void SvgCanvas::end_group() { out_ << "</g>\n"; }

void SvgCanvas::open(std::string_view element, const Tag& tag) {
  out_ << '<' << element;
  if (!tag.id.empty()) out_ << " id=\"" << escape(tag.id) << '"';
  if (!tag.cls.empty()) out_ << " class=\"" << escape(tag.cls) << '"';
}

void SvgCanvas::paint(const Paint& p) {
  out_ << " fill=\"" << colour(p.fill) << '"';
  if (!p.stroke.none) {
    out_ << " stroke=\"" << colour(p.stroke) << "\" stroke-width=\"" << f1(p.stroke_width) << '"';
    if (p.stroke_opacity < 1) out_ << " stroke-opacity=\"" << f1(p.stroke_opacity) << '"';
    if (p.dash_on > 0) {
      out_ << " stroke-dasharray=\"" << f1(p.dash_on) << ' ' << f1(p.dash_off) << '"';
    }
  }
}

void SvgCanvas::close(std::string_view element, const Tag& tag) {
  if (tag.title.empty()) {
    out_ << "/>\n";
  } else {
    out_ << "><title>" << escape(tag.title) << "</title></" << element << ">\n";
  }
}

void SvgCanvas::line(Point a, Point b, const Paint& p, const Tag& tag) {
  open("line", tag);
  out_ << " x1=\"" << f1(a.x) << "\" y1=\"" << f1(a.y) << "\" x2=\"" << f1(b.x) << "\" y2=\""
       << f1(b.y) << '"';
  paint(p);
  close("line", tag);
}

void SvgCanvas::polyline(std::span<const Point> points, const Paint& p, const Tag& tag) {
  open("polyline", tag);
  paint(p);
  out_ << " points=\"";
  for (std::size_t i = 0; i < points.size(); ++i) {
    out_ << (i == 0 ? "" : " ") << f1(points[i].x) << ',' << f1(points[i].y);
  }
  out_ << '"';
  close("polyline", tag);
}

void SvgCanvas::polygon(std::span<const Point> points, const Paint& p, const Tag& tag) {
  open("path", tag);
  out_ << " d=\"";
  for (std::size_t i = 0; i < points.size(); ++i) {
    out_ << (i == 0 ? "M" : " L") << f1(points[i].x) << ' ' << f1(points[i].y);
  }
  out_ << " Z\"";
  paint(p);
  close("path", tag);
}

void SvgCanvas::segments(std::span<const Point> points, const Paint& p, const Tag& tag) {
  open("path", tag);
  out_ << " d=\"";
  for (std::size_t i = 0; i + 1 < points.size(); i += 2) {
    out_ << (i == 0 ? "M" : " M") << f1(points[i].x) << ' ' << f1(points[i].y) << " L"
         << f1(points[i + 1].x) << ' ' << f1(points[i + 1].y);
  }
  out_ << '"';
  paint(p);
  close("path", tag);
}

void SvgCanvas::circle(Point c, double r, const Paint& p, const Tag& tag) {
  open("circle", tag);
  out_ << " cx=\"" << f1(c.x) << "\" cy=\"" << f1(c.y) << "\" r=\"" << f1(r) << '"';
  paint(p);
  close("circle", tag);
}

void SvgCanvas::rect(const Rect& r, const Paint& p, const Tag& tag) {
  open("rect", tag);
  out_ << " x=\"" << f1(r.x) << "\" y=\"" << f1(r.y) << "\" width=\"" << f1(r.width)
       << "\" height=\"" << f1(r.height) << '"';
  paint(p);
  close("rect", tag);
}

void SvgCanvas::text(Point at, std::string_view text, const Font& font, const Tag& tag) {
  open("text", tag);
  out_ << " x=\"" << f1(at.x) << "\" y=\"" << f1(at.y) << '"';
  if (font.anchor == Anchor::kMiddle) out_ << " text-anchor=\"middle\"";
  if (font.size != 11) out_ << " font-size=\"" << f1(font.size) << '"';
  if (font.bold) out_ << " font-weight=\"bold\"";
  if (font.colour.value != 0 || font.colour.none) out_ << " fill=\"" << colour(font.colour) << '"';
  out_ << '>' << escape(text) << "</text>\n";
}

Result<std::string> SvgCanvas::finish() {
  out_ << "</svg>\n";
  return out_.str();
}

}  // namespace sewerplan::render
