// SPDX-License-Identifier: MIT
// A SWMM conduit's cross-section ([XSECTIONS] row) as a sewerplan pipe profile. Private to
// core/src.
//
// Geom1 is the full height (a circle's diameter); Geom2 the width where the shape has one. Shapes
// whose width SWMM derives from the height get SWMM's ratio (xsect.c): EGG 2/3, HORSESHOE 1,
// GOTHIC 0.84, CATENARY 0.9, SEMIELLIPTICAL 1, BASKETHANDLE 0.944, SEMICIRCULAR 1.64. The pipe's
// clear size (diameter_m) is the smaller of width and height. docs/formats/swmm.md has the table.
//
//   Result<PipeProfile> p = swmm_profile(row.fields, 0.3048);  // US units: feet to metres
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::detail {

struct PipeProfile {
  PipeShape shape = PipeShape::kCircular;
  double diameter_m = 0;  // clear size
  double height_m = 0;
  int barrels = 1;
  // False where the Barrels field is not a whole number from 1 to 100: `barrels` is then 1. No plan
  // needs the count (parallel barrels are imported as one pipe); the reader warns.
  bool barrels_read = true;
  // A shape of no clear size (a V-shaped trapezoid, bottom width 0; a zero Geom): valid in SWMM,
  // no room for a robot. The reader leaves the conduit out with a warning.
  bool no_clear_size = false;
};

// The profile of an [XSECTIONS] row: fields[0] the link, [1] the shape, [2..5] Geom1..4, [6]
// barrels. kUnsupportedFormat for shapes whose size is not a number (IRREGULAR, CUSTOM, STREET,
// DUMMY: the conduit is left out); kParse, with a message naming the field, for a negative size or
// anything else wrong but the Barrels field (barrels_read).
Result<PipeProfile> swmm_profile(std::span<const std::string_view> fields, double metres_per_unit);

}  // namespace sewerplan::detail
