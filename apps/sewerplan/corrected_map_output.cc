// SPDX-License-Identifier: MIT
#include "corrected_map_output.h"

#include <cstdlib>
#include <ctime>
#include <string_view>

#include "sewerplan/core/map_io.h"
#include "sewerplan/core/measurements_json.h"
#include "sewerplan/core/output_file.h"

namespace sewerplan::cli {

std::filesystem::path beside(const std::filesystem::path& out, const std::string& what) {
  std::filesystem::path p = out;
  p.replace_extension();
  p += "." + what + ".json";
  return p;
}

std::string measurement_date() {
  std::time_t t = std::time(nullptr);
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH"); epoch != nullptr && *epoch != '\0') {
    char* end = nullptr;
    const long long v = std::strtoll(epoch, &end, 10);
    if (end != nullptr && *end == '\0' && v >= 0) t = static_cast<std::time_t>(v);
  }
  std::tm utc{};
  gmtime_r(&t, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

Result<void> write_corrected_map(const std::filesystem::path& out, const SewerMap& map,
                                 MapMeasurements& measurements, std::ostream& text) {
  measurements.discrepancies = discrepancies(measurements, map);
  Result<CorrectedMap> corrected = corrected_map(map, measurements);
  if (!corrected.has_value()) return corrected.error();
  if (Result<void> w = write_map(corrected->map, out, MapFormat::kJson); !w.has_value()) return w;
  const std::filesystem::path report = beside(out, "discrepancies");
  if (Result<void> w =
          write_text_file(report, discrepancy_report_json(*corrected, measurements, map));
      !w.has_value()) {
    return w;
  }
  std::size_t applied = 0;
  for (const auto& [found, done] : corrected->applied) applied += done ? 1U : 0U;
  text << "corrected map " << out.string() << ": " << measurements.pipes.size()
       << " pipes measured, " << measurements.discrepancies.size() << " discrepancies (" << applied
       << " applied; " << report.string() << ")\n";
  return {};
}

}  // namespace sewerplan::cli
