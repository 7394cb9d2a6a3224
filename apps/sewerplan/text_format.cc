// SPDX-License-Identifier: MIT
#include "text_format.h"

#include <cmath>
#include <cstdio>

namespace sewerplan::cli {

std::string fixed(double value, int decimals) {
  if (!std::isfinite(value)) return std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
  char buffer[64];
  const int n = std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  std::string text(buffer, n > 0 ? static_cast<std::size_t>(n) : 0);
  // -0.00: a rounding artefact, not a sign.
  if (text.front() == '-' && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
  return text;
}

}  // namespace sewerplan::cli
