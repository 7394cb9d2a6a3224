// SPDX-License-Identifier: MIT
// A corrected ISYBAU document: the source file with the values robots measured written in place.
//
// Where a map came from ISYBAU XML (map_isybau.h), the operator's sewer information system wants
// its corrections back in ISYBAU, with everything else of the file as it was: the objects and
// elements sewerplan does not read (materials, owners, Zustandsdaten, ...) included. So the
// corrected copy is not written from the SewerMap; it is the source text with the few changed
// values replaced in place, found with pugixml as the importer finds them (isybau_objects.h), and
// every other byte kept. What changes, where a corrected map (map_measurements.h: corrected_map)
// differs from the map the file gives:
//   - a Haltung's length: its Kante/Laenge (or, without one, the Rohrlaenge or DMPLaenge the
//     importer read); a Haltung with none of them gains a Laenge before its Profil, where the
//     schema puts it;
//   - a node's position: Rechtswert and Hochwert of its first Punkt, by the measured shift (so a
//     UTM zone in front of the Rechtswert stays);
//   - a pipe's diameter (smaller than mapped): Profilbreite, and a circle's Profilhoehe.
// Each changed element gets an XML comment before it ("sewerplan: Laenge measured ..., was ...").
// ISYBAU has no element for who measured (Stammdaten record the object, not a survey), so the
// provenance (robots, missions, dates) is an XML comment before the root element. Slot directions
// are not written: in ISYBAU they follow from the pipes' lines, which no robot measured; each such
// correction is a warning, as is a position of a node without a Punkt. The file is written in
// the encoding it was read in (Latin-1 stays Latin-1, a byte-order mark stays).
//
//   Result<CorrectedMap> fixed = corrected_map(map, measurements);
//   Result<IsybauCorrection> xml = correct_isybau(source_text, "street.xml", *fixed,
//                                                 measurements, diagnostics);
//   write_text_file("street-corrected.xml", xml->text);
//
// Thread safety: a pure function.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/map_isybau.h"
#include "sewerplan/core/map_measurements.h"
#include "sewerplan/core/result.h"

namespace sewerplan {

struct IsybauCorrection {
  std::string text;         // the document, in the source's encoding
  std::size_t lengths = 0;  // values changed
  std::size_t positions = 0;
  std::size_t diameters = 0;
};

// The ISYBAU text `source` (the file `file_name`, for messages) with `corrected`'s values written
// in place (above). `measurements` are the ones `corrected` was made from: their fingerprint must
// be that of the map `source` gives (read with `options`), else kInvalidArgument naming both maps
// and fingerprints; `corrected` must have that map's pipes and manholes, by name. A source that
// does not read is its read error; one whose bytes are no characters in its encoding (they
// could not be kept) is kUnsupportedFormat. Warnings (values not written) into `diagnostics`.
// Runtime: O(size of the source).
Result<IsybauCorrection> correct_isybau(std::string_view source, const std::string& file_name,
                                        const CorrectedMap& corrected,
                                        const MapMeasurements& measurements,
                                        Diagnostics& diagnostics,
                                        const IsybauImportOptions& options = {});

}  // namespace sewerplan
