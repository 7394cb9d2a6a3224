// SPDX-License-Identifier: MIT
// datasets/isybau/street-2017.xml placed on the earth: every Rechtswert and Hochwert moved by
// (477000, 5760000) and each object's Geometrie given `lagesystem` (e.g. "ETRS89_UTM32") in an
// element named `crs_element` (Lagesystem, or CRSLage as the official samples and real exports
// write it), so its S1 stands at E 477000, N 5760000 in ETRS89 / UTM zone 32N (EPSG:25832).
#pragma once

#include <regex>
#include <string>

#include "sewerplan/core/text_file.h"

#include "support/paths.h"

namespace sewerplan::testing {

inline constexpr double kStreetEasting = 477000;
inline constexpr double kStreetNorthing = 5760000;

inline std::string georeferenced_street(const std::string& lagesystem,
                                        const std::string& crs_element = "Lagesystem") {
  std::string text = read_text_file(dataset_path("isybau/street-2017.xml")).value();
  const auto shift = [](const std::string& in, const std::string& element, double by) {
    const std::regex pattern("<" + element + ">([-0-9.]+)</" + element + ">");
    std::string out;
    auto begin = std::sregex_iterator(in.begin(), in.end(), pattern);
    std::size_t last = 0;
    for (auto it = begin; it != std::sregex_iterator(); ++it) {
      out += in.substr(last, static_cast<std::size_t>(it->position()) - last);
      out += "<" + element + ">" + std::to_string(std::stod((*it)[1].str()) + by) + "</" + element +
             ">";
      last = static_cast<std::size_t>(it->position() + it->length());
    }
    return out + in.substr(last);
  };
  text = shift(text, "Rechtswert", kStreetEasting);
  text = shift(text, "Hochwert", kStreetNorthing);
  if (!lagesystem.empty()) {
    text = std::regex_replace(
        text, std::regex("<Geometrie>"),
        "<Geometrie><" + crs_element + ">" + lagesystem + "</" + crs_element + ">");
  }
  return text;
}

}  // namespace sewerplan::testing
