// SPDX-License-Identifier: MIT
// Where an ISYBAU network lies: its coordinate reference system and the lines of its Haltungen.
// Private to core/src: the geometry half of the ISYBAU importer (map_isybau.cc reads the objects,
// their names, shafts and profiles, and calls these).
//
// The CRS comes from the objects' CRSLage elements, or Lagesystem in older files, as AdV names
// ("ETRS89_UTM32", "DE_DHDN_3GK3_NW177") or EPSG codes. Rechtswerte in a UTM CRS often carry the
// zone number in front (32570429.70), which strip_utm_zone_prefix removes. A Haltung's line is
// its segments (2013), its open polygon (2017) or its points (2006), cut at the pipe's mouths in
// the shaft walls (RAP points) where the file marks them: the ends of the line then give the
// directions of the pipe's slots in its manholes.
//
// Thread safety: Free functions that share nothing.
#pragma once

#include <optional>
#include <string>

#include <pugixml.hpp>

#include "sewerplan/core/crs.h"
#include "sewerplan/core/diagnostics.h"

#include "network_import.h"

namespace sewerplan::detail {

// The position reference of the network: the CRSLage elements of its objects' geometry (the
// official 2013 and 2017 samples and real exports), or Lagesystem (older writers). One the reader
// does not know, or two that differ, are a warning at the element and no CRS (give --crs).
std::optional<Crs> read_isybau_crs(pugi::xml_node root, const std::string& file, Diagnostics& d);

// With a UTM CRS (EPSG:25832, 25833) in `net`, every Rechtswert of the form zone x 10^6 + an
// easting below 10^6 is read as the easting, with one warning counting them.
void strip_utm_zone_prefix(NetworkImport& net, const std::string& file, Diagnostics& d);

// The line of the Haltung `object` into link.vertices (every point, node ends included), and
// link.starts_at_mouth where RAP points mark the pipe's mouths. A point without a number is an
// error at its element.
void read_isybau_line(pugi::xml_node object, const std::string& file, Diagnostics& d,
                      ImportLink& link);

// The length of the pipe's line, from node to node: its vertices, with the nodes' positions at
// either end where known. None with fewer than two points.
std::optional<double> line_length(const ImportLink& link, const ImportNode* from,
                                  const ImportNode* to);

}  // namespace sewerplan::detail
