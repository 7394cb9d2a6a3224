// SPDX-License-Identifier: MIT
#include "corrected_map_output.h"

#include <cstdlib>
#include <ctime>
#include <optional>
#include <string_view>

#include "sewerplan/core/isybau_correction.h"
#include "sewerplan/core/map_io.h"
#include "sewerplan/core/measurements_json.h"
#include "sewerplan/core/output_file.h"
#include "sewerplan/core/text_file.h"

#include "output_format.h"

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

namespace {

// What --corrected-map names (output_format.h): our JSON map, the default, or ISYBAU XML too.
constexpr OutputExtension kCorrectedMapFormats[] = {{".json", "json"}, {".xml", "xml"}};

bool names_xml(const std::filesystem::path& out) {
  const Result<std::string_view> format = output_format(out, "", kCorrectedMapFormats);
  return format.has_value() && *format == "xml";
}

// The text of `map_source` if it is an ISYBAU file (what the map was read from), else nothing.
std::optional<std::string> isybau_source(const std::string& map_source) {
  if (map_source.empty() || is_gis_source_path(map_source)) return std::nullopt;
  Result<std::string> text = read_text_file(map_source);
  if (!text.has_value()) return std::nullopt;
  const Result<MapFormat> format = detect_map_format(map_source, *text);
  if (!format.has_value() || *format != MapFormat::kIsybau) return std::nullopt;
  return std::move(*text);
}

std::filesystem::path with_extension(std::filesystem::path p, const char* extension) {
  p.replace_extension(extension);
  return p;
}

}  // namespace

Result<void> check_corrected_map_target(const std::filesystem::path& out,
                                        const std::string& map_source) {
  if (Result<std::string_view> format = output_format(out, "--corrected-map", kCorrectedMapFormats);
      !format.has_value()) {
    return format.error();
  }
  if (!names_xml(out) || isybau_source(map_source)) return {};
  return Error{ErrorCode::kInvalidArgument,
               "--corrected-map " + out.string() +
                   ": ISYBAU XML is written only for a map read from ISYBAU XML, and " +
                   map_source + " is not; give a .json name"};
}

Result<void> write_corrected_map(const std::filesystem::path& out, const std::string& map_source,
                                 const SewerMap& map, MapMeasurements& measurements,
                                 std::ostream& text, Diagnostics& diagnostics) {
  if (Result<void> ok = check_corrected_map_target(out, map_source); !ok.has_value()) return ok;
  measurements.discrepancies = discrepancies(measurements, map);
  Result<CorrectedMap> corrected = corrected_map(map, measurements);
  if (!corrected.has_value()) return corrected.error();
  const std::filesystem::path json = names_xml(out) ? with_extension(out, ".json") : out;
  if (Result<void> w = write_map(corrected->map, json, MapFormat::kJson); !w.has_value()) return w;
  const std::filesystem::path report = beside(out, "discrepancies");
  if (Result<void> w =
          write_text_file(report, discrepancy_report_json(*corrected, measurements, map));
      !w.has_value()) {
    return w;
  }
  std::size_t applied = 0;
  for (const auto& [found, done] : corrected->applied) applied += done ? 1U : 0U;
  text << "corrected map " << json.string() << ": " << measurements.pipes.size()
       << " pipes measured, " << measurements.discrepancies.size() << " discrepancies (" << applied
       << " applied; " << report.string() << ")\n";
  if (const std::optional<std::string> source = isybau_source(map_source)) {
    const std::filesystem::path xml = with_extension(out, ".xml");
    Result<IsybauCorrection> isybau =
        correct_isybau(*source, map_source, *corrected, measurements, diagnostics);
    if (!isybau.has_value()) return isybau.error();
    if (Result<void> w = write_text_file(xml, isybau->text); !w.has_value()) return w;
    text << "corrected ISYBAU " << xml.string() << ": " << isybau->lengths << " lengths, "
         << isybau->positions << " positions, " << isybau->diameters << " diameters changed in "
         << map_source << "'s text\n";
  }
  return {};
}

}  // namespace sewerplan::cli
