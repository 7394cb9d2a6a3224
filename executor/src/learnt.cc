// SPDX-License-Identifier: MIT
// The learnt-knowledge file (docs/executor.md): read through core's JSON reader (json_fields.h),
// as every file of sewerplan is; written with nlohmann::json. Unlike hand-written files, an
// unknown field is an error here: sewerplan writes these files itself.
#include "sewerplan/executor/learnt.h"

#include <cmath>
#include <optional>

#include <nlohmann/json.hpp>

#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/text_file.h"

namespace sewerplan::executor {
namespace {

using json = nlohmann::ordered_json;
using Need = JsonFields::Need;

class LearntReader {
 public:
  LearntReader(const SewerMap& map, const std::string& file, Diagnostics& diagnostics)
      : map_(map), file_(file), diagnostics_(diagnostics) {}

  std::optional<PipeId> pipe(JsonFields& f) {
    const std::optional<std::string> name = f.string("pipe");
    if (!name) return std::nullopt;
    if (auto id = map_.find_pipe(*name)) return id;
    f.error("pipe", "unknown pipe \"" + *name + "\"");
    return std::nullopt;
  }

  std::optional<Blockage> in_pipe(JsonElement element, const std::string& path) {
    JsonFields f(element, path, file_, diagnostics_);
    f.reject_unknown({"pipe", "offset_m"});
    const auto p = pipe(f);
    if (!p) return std::nullopt;
    const Pipe& pipe = map_.pipe(*p);
    const std::optional<double> offset = f.number("offset_m", Need::kOptional);
    if (f.has("offset_m") && !offset) return std::nullopt;  // not a number: reported
    if (!offset || !std::isfinite(*offset) || *offset < 0 || *offset > pipe.length_m) {
      f.error("offset_m", "expected an offset from 0 to " + json(pipe.length_m).dump() +
                              " m (the length of pipe " + pipe.name + ")");
      return std::nullopt;
    }
    return Blockage{*p, *offset};
  }

  std::optional<ClosedPassage> passage(JsonElement element, const std::string& path) {
    JsonFields f(element, path, file_, diagnostics_);
    f.reject_unknown({"manhole", "from_slot", "to_slot"});
    const std::optional<std::string> name = f.string("manhole");
    if (!name) return std::nullopt;
    const auto m = map_.find_manhole(*name);
    if (!m) {
      f.error("manhole", "unknown manhole \"" + *name + "\"");
      return std::nullopt;
    }
    const std::size_t slots = map_.slots(*m).size();
    auto slot = [&](std::string_view key) -> std::optional<SlotIndex> {
      const std::optional<double> v = f.number(key, Need::kOptional);
      if (f.has(key) && !v) return std::nullopt;  // not a number: reported
      if (!v || std::floor(*v) != *v || *v < 1 || *v > static_cast<double>(slots)) {
        f.error(key, "expected a slot of manhole " + *name + " from 1 to " + std::to_string(slots));
        return std::nullopt;
      }
      return SlotIndex{static_cast<std::uint16_t>(*v - 1)};
    };
    const auto from = slot("from_slot");
    const auto to = slot("to_slot");
    if (!from || !to) return std::nullopt;
    if (*from == *to) {
      f.error("to_slot", "a passage from a slot to itself");
      return std::nullopt;
    }
    return ClosedPassage{*m, *from, *to};
  }

  template <class T, class Read>
  void each(JsonFields& root, std::string_view key, std::vector<T>& out, Read read) {
    const std::optional<JsonArray> items = root.array(key, Need::kOptional);
    if (!items) return;
    std::size_t i = 0;
    for (JsonElement item : *items) {
      if (auto v = read(item, indexed("$." + std::string(key), i++))) out.push_back(*v);
    }
  }

 private:
  const SewerMap& map_;
  const std::string& file_;
  Diagnostics& diagnostics_;
};

}  // namespace

Mission with_learnt(Mission mission, const Learnt& learnt) {
  mission.blockages.insert(mission.blockages.end(), learnt.blockages.begin(),
                           learnt.blockages.end());
  mission.blockages.insert(mission.blockages.end(), learnt.danger_spots.begin(),
                           learnt.danger_spots.end());
  mission.closed_passages.insert(mission.closed_passages.end(), learnt.closed_passages.begin(),
                                 learnt.closed_passages.end());
  return mission;
}

Result<Learnt> read_learnt_json(std::string_view text, const std::string& file_name,
                                const SewerMap& map, Diagnostics& diagnostics) {
  const Diagnostics::Mark before = diagnostics.mark();
  const std::optional<JsonDocument> doc = JsonDocument::parse(text, file_name, diagnostics);
  if (!doc) return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  JsonFields root(doc->root(), "$", file_name, diagnostics);
  if (!root.is_object()) return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  root.reject_unknown({"format", "version", "blockages", "danger", "closed_passages"});
  // Absent or another value: one error each (a value of the wrong type is JsonFields' error).
  const std::optional<std::string> format = root.string("format", Need::kOptional);
  if (format ? *format != kLearntJsonFormat : !root.has("format")) {
    root.error("format", "expected \"" + std::string(kLearntJsonFormat) + "\"");
  }
  const std::optional<double> version = root.number("version", Need::kOptional);
  if (version ? *version != static_cast<double>(kLearntJsonVersion) : !root.has("version")) {
    root.error("version", "expected " + std::to_string(kLearntJsonVersion));
  }
  LearntReader reader(map, file_name, diagnostics);
  Learnt learnt;
  const auto in_pipe = [&](JsonElement e, const std::string& path) {
    return reader.in_pipe(e, path);
  };
  reader.each(root, "blockages", learnt.blockages, in_pipe);
  reader.each(root, "danger", learnt.danger_spots, in_pipe);
  reader.each(root, "closed_passages", learnt.closed_passages,
              [&](JsonElement e, const std::string& path) { return reader.passage(e, path); });
  if (diagnostics.has_errors_since(before))
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  return learnt;
}

Result<Learnt> read_learnt(const std::filesystem::path& path, const SewerMap& map,
                           Diagnostics& diagnostics) {
  Result<std::string> text = read_text_file(path);
  if (!text.has_value()) return text.error();
  return read_learnt_json(*text, path.string(), map, diagnostics);
}

std::string learnt_json(const Learnt& learnt, const SewerMap& map) {
  json j;
  j["format"] = std::string(kLearntJsonFormat);
  j["version"] = kLearntJsonVersion;
  const auto in_pipe = [&](const std::vector<Blockage>& list) {
    json a = json::array();
    for (const Blockage& b : list) {
      a.push_back({{"pipe", map.pipe(b.pipe).name}, {"offset_m", b.offset_m}});
    }
    return a;
  };
  j["blockages"] = in_pipe(learnt.blockages);
  j["danger"] = in_pipe(learnt.danger_spots);
  j["closed_passages"] = json::array();
  for (const ClosedPassage& p : learnt.closed_passages) {
    j["closed_passages"].push_back({{"manhole", map.manhole(p.manhole).name},
                                    {"from_slot", to_paper_number(p.from)},
                                    {"to_slot", to_paper_number(p.to)}});
  }
  return j.dump(2) + "\n";
}

}  // namespace sewerplan::executor
