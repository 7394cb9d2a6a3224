// SPDX-License-Identifier: MIT
// A Canvas drawn by cairo and written as PNG (png_canvas.h).
#include "png_canvas.h"

#include <cmath>

#include <cairo.h>

namespace sewerplan::render {

struct PngCanvas::Cairo {
  cairo_surface_t* surface = nullptr;
  cairo_t* cr = nullptr;
  ~Cairo() {
    if (cr != nullptr) cairo_destroy(cr);
    if (surface != nullptr) cairo_surface_destroy(surface);
  }
};

namespace {

void source(cairo_t* cr, Colour c, double alpha = 1) {
  cairo_set_source_rgba(cr, ((c.value >> 16) & 0xff) / 255.0, ((c.value >> 8) & 0xff) / 255.0,
                        (c.value & 0xff) / 255.0, alpha);
}

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

PngCanvas::PngCanvas() = default;
PngCanvas::~PngCanvas() = default;

Result<void> PngCanvas::begin(double width, double height) {
  const double w = std::ceil(width);
  const double h = std::ceil(height);
  if (!(w >= 1 && h >= 1 && w <= 32767 && h <= 32767 && w * h <= 100e6)) {
    return Error{ErrorCode::kInvalidArgument,
                 "a PNG of " + std::to_string(std::lround(w)) + " x " +
                     std::to_string(std::lround(h)) +
                     " pixels is too large (at most 32767 a side and 100 million pixels)"};
  }
  cairo_ = std::make_unique<Cairo>();
  cairo_->surface =
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(w), static_cast<int>(h));
  if (cairo_surface_status(cairo_->surface) != CAIRO_STATUS_SUCCESS) {
    return Error{
        ErrorCode::kInvalidArgument,
        std::string("cairo: ") + cairo_status_to_string(cairo_surface_status(cairo_->surface))};
  }
  cairo_->cr = cairo_create(cairo_->surface);
  cairo_t* cr = cairo_->cr;
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  return {};
}

void PngCanvas::begin_group(std::string_view, const Rect* clip) {
  cairo_t* cr = cairo_->cr;
  cairo_save(cr);
  if (clip != nullptr) {
    cairo_rectangle(cr, clip->x, clip->y, clip->width, clip->height);
    cairo_clip(cr);
  }
}

void PngCanvas::end_group() { cairo_restore(cairo_->cr); }

// Fills and strokes the current path.
void PngCanvas::draw(const Paint& p) {
  cairo_t* cr = cairo_->cr;
  if (!p.fill.none) {
    source(cr, p.fill);
    if (p.stroke.none) {
      cairo_fill(cr);
      return;
    }
    cairo_fill_preserve(cr);
  }
  if (p.stroke.none) {
    cairo_new_path(cr);
    return;
  }
  source(cr, p.stroke, p.stroke_opacity);
  cairo_set_line_width(cr, p.stroke_width);
  if (p.dash_on > 0) {
    const double dashes[2] = {p.dash_on, p.dash_off};
    cairo_set_dash(cr, dashes, 2, 0);
  }
  cairo_stroke(cr);
  if (p.dash_on > 0) cairo_set_dash(cr, nullptr, 0, 0);
}

void PngCanvas::line(Point a, Point b, const Paint& p, const Tag&) {
  cairo_move_to(cairo_->cr, a.x, a.y);
  cairo_line_to(cairo_->cr, b.x, b.y);
  draw(p);
}

void PngCanvas::polyline(std::span<const Point> points, const Paint& p, const Tag&) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i == 0) {
      cairo_move_to(cairo_->cr, points[i].x, points[i].y);
    } else {
      cairo_line_to(cairo_->cr, points[i].x, points[i].y);
    }
  }
  draw(p);
}

void PngCanvas::polygon(std::span<const Point> points, const Paint& p, const Tag&) {
  if (points.empty()) return;
  cairo_move_to(cairo_->cr, points[0].x, points[0].y);
  for (const Point& q : points.subspan(1)) cairo_line_to(cairo_->cr, q.x, q.y);
  cairo_close_path(cairo_->cr);
  draw(p);
}

void PngCanvas::segments(std::span<const Point> points, const Paint& p, const Tag&) {
  for (std::size_t i = 0; i + 1 < points.size(); i += 2) {
    cairo_move_to(cairo_->cr, points[i].x, points[i].y);
    cairo_line_to(cairo_->cr, points[i + 1].x, points[i + 1].y);
  }
  draw(p);
}

void PngCanvas::circle(Point c, double r, const Paint& p, const Tag&) {
  cairo_new_sub_path(cairo_->cr);
  cairo_arc(cairo_->cr, c.x, c.y, r, 0, 2 * M_PI);
  draw(p);
}

void PngCanvas::rect(const Rect& r, const Paint& p, const Tag&) {
  cairo_rectangle(cairo_->cr, r.x, r.y, r.width, r.height);
  draw(p);
}

void PngCanvas::text(Point at, std::string_view text, const Font& font, const Tag&) {
  cairo_t* cr = cairo_->cr;
  const std::string s(text);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         font.bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, font.size);
  double x = at.x;
  if (font.anchor == Anchor::kMiddle) {
    cairo_text_extents_t extents;
    cairo_text_extents(cr, s.c_str(), &extents);
    x -= extents.x_advance / 2;
  }
  source(cr, font.colour);
  cairo_move_to(cr, x, at.y);
  cairo_show_text(cr, s.c_str());
  cairo_new_path(cr);
}

Result<std::string> PngCanvas::finish() {
  if (cairo_ == nullptr) return Error{ErrorCode::kInvalidArgument, "PngCanvas: begin not called"};
  cairo_surface_flush(cairo_->surface);
  std::string png;
  const cairo_status_t status = cairo_surface_write_to_png_stream(cairo_->surface, append, &png);
  if (status != CAIRO_STATUS_SUCCESS) {
    return Error{ErrorCode::kIo, std::string("cairo: ") + cairo_status_to_string(status)};
  }
  return png;
}

}  // namespace sewerplan::render
