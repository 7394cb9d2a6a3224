// SPDX-License-Identifier: MIT
#include "swmm_xsection.h"

#include <algorithm>
#include <array>
#include <optional>

#include "sewerplan/core/message_text.h"

#include "swmm_sections.h"

namespace sewerplan::detail {
namespace {

enum class Width { kCircle, kGeom2, kRatio, kNone };

struct ShapeSpec {
  std::string_view name;
  PipeShape shape;
  Width width;
  double ratio = 0;  // width / height, for Width::kRatio
};

constexpr auto kShapes = std::to_array<ShapeSpec>({
    {"CIRCULAR", PipeShape::kCircular, Width::kCircle},
    {"FORCE_MAIN", PipeShape::kCircular, Width::kCircle},
    {"FILLED_CIRCULAR", PipeShape::kOther, Width::kCircle},
    {"RECT_CLOSED", PipeShape::kRectangular, Width::kGeom2},
    {"RECT_OPEN", PipeShape::kRectangular, Width::kGeom2},
    {"RECT_TRIANGULAR", PipeShape::kOther, Width::kGeom2},
    {"RECT_ROUND", PipeShape::kOther, Width::kGeom2},
    {"MODBASKETHANDLE", PipeShape::kOther, Width::kGeom2},
    {"TRAPEZOIDAL", PipeShape::kOther, Width::kGeom2},
    {"TRIANGULAR", PipeShape::kOther, Width::kGeom2},
    {"PARABOLIC", PipeShape::kOther, Width::kGeom2},
    {"POWER", PipeShape::kOther, Width::kGeom2},
    {"HORIZ_ELLIPSE", PipeShape::kOther, Width::kGeom2},
    {"VERT_ELLIPSE", PipeShape::kOther, Width::kGeom2},
    {"ARCH", PipeShape::kOther, Width::kGeom2},
    {"EGG", PipeShape::kEgg, Width::kRatio, 2.0 / 3.0},
    {"HORSESHOE", PipeShape::kOther, Width::kRatio, 1.0},
    {"GOTHIC", PipeShape::kOther, Width::kRatio, 0.84},
    {"CATENARY", PipeShape::kOther, Width::kRatio, 0.9},
    {"SEMIELLIPTICAL", PipeShape::kOther, Width::kRatio, 1.0},
    {"BASKETHANDLE", PipeShape::kOther, Width::kRatio, 0.944},
    {"SEMICIRCULAR", PipeShape::kOther, Width::kRatio, 1.64},
    {"IRREGULAR", PipeShape::kOther, Width::kNone},
    {"CUSTOM", PipeShape::kOther, Width::kNone},
    {"STREET", PipeShape::kOther, Width::kNone},
    {"DUMMY", PipeShape::kOther, Width::kNone},
});

Error bad(std::string message) { return Error{ErrorCode::kParse, std::move(message)}; }

}  // namespace

Result<PipeProfile> swmm_profile(std::span<const std::string_view> fields, double metres_per_unit) {
  if (fields.size() < 3) return bad("expected at least: link, shape, Geom1");
  const std::string name = to_upper(fields[1]);
  const auto spec = std::find_if(kShapes.begin(), kShapes.end(),
                                 [&](const ShapeSpec& s) { return s.name == name; });
  if (spec == kShapes.end()) return bad("unknown cross-section shape " + input_quoted(fields[1]));
  if (spec->width == Width::kNone) {
    return Error{ErrorCode::kUnsupportedFormat,
                 "shape " + name + " has no dimensions in [XSECTIONS]"};
  }
  auto geom = [&](std::size_t k) -> Result<double> {
    if (fields.size() <= k + 1) return bad("missing Geom" + std::to_string(k));
    const std::optional<double> v = parse_swmm_number(fields[k + 1]);
    if (!v)
      return bad("Geom" + std::to_string(k) + " is not a number: " + input_quoted(fields[k + 1]));
    return *v * metres_per_unit;
  };
  Result<double> height = geom(1);
  if (!height.has_value()) return height.error();
  PipeProfile p{.shape = spec->shape, .height_m = *height};
  double width = *height;
  switch (spec->width) {
    case Width::kCircle:
      if (name == "FILLED_CIRCULAR") {
        Result<double> filled = geom(2);
        if (!filled.has_value()) return filled.error();
        p.height_m = *height - *filled;
      }
      break;
    case Width::kGeom2: {
      Result<double> w = geom(2);
      if (!w.has_value()) return w.error();
      width = *w;
      break;
    }
    case Width::kRatio:
      width = *height * spec->ratio;
      break;
    case Width::kNone:
      break;
  }
  p.diameter_m = std::min(width, p.height_m);
  if (p.diameter_m < 0) return bad("negative size: " + number_text(p.diameter_m) + " m");
  p.no_clear_size = !(p.diameter_m > 0);  // also NaN
  if (fields.size() > 6) {
    const std::optional<double> barrels = parse_swmm_number(fields[6]);
    if (!barrels || !(*barrels >= 1 && *barrels <= 100) || *barrels != static_cast<int>(*barrels)) {
      p.barrels_read = false;
    } else {
      p.barrels = static_cast<int>(*barrels);
    }
  }
  return p;
}

}  // namespace sewerplan::detail
