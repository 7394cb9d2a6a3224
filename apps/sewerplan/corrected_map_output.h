// SPDX-License-Identifier: MIT
// What simulate --corrected-map and merge-measurements write: the corrected map (our JSON map),
// the discrepancy report beside it (OUT.discrepancies.json), and, when asked, the measurements.
// Where the map was read from ISYBAU XML, the corrected map is also written as ISYBAU XML
// (core/isybau_correction.h: the source file with the measured values changed in place): OUT.xml
// beside OUT.json. OUT may name either: `--corrected-map fixed.xml` writes fixed.xml and
// fixed.json (docs/cli.md).
#pragma once

#include <filesystem>
#include <ostream>
#include <string>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/map_measurements.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::cli {

// OUT.discrepancies.json, OUT.measurements.json: beside OUT, its extension replaced.
std::filesystem::path beside(const std::filesystem::path& out, const std::string& what);

// The date of a measurement: SOURCE_DATE_EPOCH's when set (reproducible outputs), else now; ISO
// 8601 UTC.
std::string measurement_date();

// Whether --corrected-map `out` can be written for the map file `map_source`: OUT ends in .json or
// .xml (or has no extension: JSON; output_format.h), and an .xml OUT only for a map read from
// ISYBAU XML (else kInvalidArgument, a usage error, naming the file). Asked before a mission, so
// that its measurements are not lost to a name.
Result<void> check_corrected_map_target(const std::filesystem::path& out,
                                        const std::string& map_source);

// Derives the discrepancies of `measurements` (into it), builds the corrected map and writes it to
// `out` (and OUT.xml, for a map read from the ISYBAU file `map_source`) with its discrepancy report
// beside it; says on `text` what it wrote; what the ISYBAU copy could not carry (slot directions)
// is a warning in `diagnostics`. Errors: kIo naming the file (exit 3), or the map that would not
// validate.
Result<void> write_corrected_map(const std::filesystem::path& out, const std::string& map_source,
                                 const SewerMap& map, MapMeasurements& measurements,
                                 std::ostream& text, Diagnostics& diagnostics);

}  // namespace sewerplan::cli
