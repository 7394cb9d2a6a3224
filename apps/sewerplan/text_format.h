// SPDX-License-Identifier: MIT
// Numbers in the CLI's text output, one fixed precision per quantity (docs/cli.md, "Numbers"):
// metres 2 decimals, seconds 1, milliseconds 1, watt-hours 1 (as the library's messages say
// "needs 595.2 Wh"), degrees 2. JSON output keeps full precision; these are for people. GCC 12
// has no <format>, so this is snprintf underneath.
//
//   err << "plan: " << steps << " steps, " << seconds(cost_s) << ", " << watt_hours(wh) << '\n';
//   // plan: 14 steps, 585.4 s, 19.5 Wh
#pragma once

#include <string>

namespace sewerplan::cli {

// `value` with `decimals` digits after the point ("-0.00" is printed "0.00").
std::string fixed(double value, int decimals);

inline std::string metres(double m) { return fixed(m, 2) + " m"; }
inline std::string seconds(double s) { return fixed(s, 1) + " s"; }
inline std::string milliseconds(double s) { return fixed(s * 1e3, 1) + " ms"; }
inline std::string watt_hours(double wh) { return fixed(wh, 1) + " Wh"; }
inline std::string degrees(double deg) { return fixed(deg, 2) + " deg"; }

}  // namespace sewerplan::cli
