// SPDX-License-Identifier: MIT
// The measurements file (format "sewerplan-measurements", version 1; docs/formats/
// measurements-json.md) and the discrepancy report written beside a corrected map.
//
// What robots measured of a map (map_measurements.h) is saved as JSON naming the map's pipes and
// manholes and carrying the map's name and geometry fingerprint: read against another map, it is
// an error at $.map.fingerprint. It is read through core's one JSON reader (json_fields.h), every
// problem a diagnostic "file:$.pipes[3].length_m: ..."; an unknown member is an error, as in
// every file sewerplan writes and reads back itself.
//
//   Diagnostics d;
//   Result<MapMeasurements> m = read_measurements("run1.measurements.json", map, d);
//   write_text_file("merged.json", measurements_json(*merged, map));
//
// Thread safety: pure functions.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "sewerplan/core/diagnostics.h"
#include "sewerplan/core/map_measurements.h"
#include "sewerplan/core/result.h"
#include "sewerplan/core/sewer_map.h"

namespace sewerplan {

inline constexpr std::string_view kMeasurementsJsonFormat = "sewerplan-measurements";
inline constexpr int kMeasurementsJsonVersion = 1;
inline constexpr std::string_view kDiscrepancyReportFormat = "sewerplan-discrepancies";
inline constexpr int kDiscrepancyReportVersion = 1;

// Reads the format against `map`: names resolved, slots from 1, every number checked (finite,
// variances > 0, offsets within their pipe, signatures as check_signature wants, sources indices
// into $.sources). kParse with every problem in `diagnostics`.
Result<MapMeasurements> read_measurements_json(std::string_view text, const std::string& file_name,
                                               const SewerMap& map, Diagnostics& diagnostics);
Result<MapMeasurements> read_measurements(const std::filesystem::path& path, const SewerMap& map,
                                          Diagnostics& diagnostics);
// The JSON text; read_measurements_json reads it back to equal measurements.
std::string measurements_json(const MapMeasurements& measurements, const SewerMap& map);

// The discrepancy report: the map and the sources, and each discrepancy with its describe() text,
// value, map value, sigma, the missions that show it, and whether the corrected map carries it.
std::string discrepancy_report_json(const CorrectedMap& corrected,
                                    const MapMeasurements& measurements, const SewerMap& map);

}  // namespace sewerplan
