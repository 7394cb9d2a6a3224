// SPDX-License-Identifier: MIT
// Importing ISYBAU XML: the exchange format of German sewer information systems.
//
// ISYBAU ("Arbeitshilfen Abwasser" of the German federal building administration) describes every
// object of a drainage network as an AbwassertechnischeAnlage: Objektart 2 is a node (Knoten;
// KnotenTyp 0 Schacht = manhole, 1 Anschlusspunkt = connection point, 2 Bauwerk = structure), and
// Objektart 1 an edge (Kante; KantenTyp 0 Haltung = a sewer pipe between manholes, 1 Leitung = a
// lateral, 2 Rinne = a channel). read_map_isybau turns each manhole and structure into a manhole
// and each Haltung into a pipe: KnotenZulauf / KnotenAblauf name its upstream and downstream node,
// SohlhoeheZulauf / SohlhoeheAblauf its end inverts (so the steps in each manhole), Laenge its
// length, Profil its size (millimetres in the file), Schacht/Unterteil a manhole's size; the
// nodes' point geometry (Rechtswert, Hochwert, Punkthoehe) gives positions and, with the pipes'
// own geometry (skipping points inside the shaft, such as 2013's floor points), each slot's
// azimuth. The elements the schema makes optional fall back with warnings; Zustandsdaten
// (inspection findings) in the same file are read into the map (condition.h). Latin-1 and
// Windows-1252 files are converted to UTF-8 first.
//
// Versions 2006, 2013 and 2017 are read alike: elements are matched by their local name, so each
// version's namespace is accepted, and both ways of storing a pipe's line (2006: a Polygon of
// Punkte; 2013 and 2017: Kante segments with Start and Ende) are understood. Names are unique per
// object kind only: a Haltung usually bears its upstream manhole's name, which is fine, as
// manholes and pipes are separate kinds. Laterals, channels and connection points are not drivable
// and are left out, counted in a warning; a Haltung ending at a connection point has a blind end
// there. Field by field, with every default and warning: docs/formats/isybau.md.
//
//   Diagnostics diagnostics;
//   Result<SewerMap> map = read_map_isybau(text, "datasets/isybau/street-2017.xml", diagnostics);
//   // errors name the element: "street.xml:/Identifikation/.../AbwassertechnischeAnlage[3]/..."
//
// Thread safety: The importer shares nothing: call it from any number of threads, each with its own
// Diagnostics.
#pragma once

#include <string>
#include <string_view>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

struct IsybauImportOptions {
  // The diameter of manholes whose shaft size (Schacht/Unterteil) the file does not give, in
  // metres (> 0).
  double manhole_diameter_m = 1.0;
};

// Reads a map from `text`, the content of the ISYBAU XML file `file_name` (its stem names the
// map). XML that is not well-formed is a kParse error at "file:line"; a missing or malformed
// field is a kParse error naming the element's path; the network's problems (unknown nodes,
// duplicate names, ...) are MapBuilder's kInvalidMap errors at the object's element path. Never
// throws, whatever the input. Runtime: O(n log n) in the size of the text.
Result<SewerMap> read_map_isybau(std::string_view text, const std::string& file_name,
                                 Diagnostics& diagnostics, const IsybauImportOptions& options = {});

}  // namespace sewerplan
