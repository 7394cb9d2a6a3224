// SPDX-License-Identifier: MIT
// What simulate --corrected-map and merge-measurements write: the corrected map (our JSON map),
// the discrepancy report beside it (OUT.discrepancies.json), and, when asked, the measurements.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>

#include "sewerplan/core/map_measurements.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan::cli {

// OUT.discrepancies.json, OUT.measurements.json: beside OUT, its extension replaced.
std::filesystem::path beside(const std::filesystem::path& out, const std::string& what);

// The date of a measurement: SOURCE_DATE_EPOCH's when set (reproducible outputs), else now; ISO
// 8601 UTC.
std::string measurement_date();

// Derives the discrepancies of `measurements` (into it), builds the corrected map and writes it to
// `out` with its discrepancy report beside it; says on `text` what it wrote. Errors: kIo naming
// the file (exit 3), or the map that would not validate.
Result<void> write_corrected_map(const std::filesystem::path& out, const SewerMap& map,
                                 MapMeasurements& measurements, std::ostream& text);

}  // namespace sewerplan::cli
