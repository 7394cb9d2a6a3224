// SPDX-License-Identifier: MIT
// The learnt-knowledge file (docs/executor.md), read and written with nlohmann::json as the other
// small files of the robot's side are (hal/src/fault_json.cc); syntax errors are located by
// core's one locator (report_json_syntax_error).
#include "sewerplan/executor/learnt.h"

#include <cmath>
#include <optional>

#include <nlohmann/json.hpp>

#include "sewerplan/core/text_file.h"

namespace sewerplan::executor {
namespace {

using json = nlohmann::ordered_json;

class LearntReader {
 public:
  LearntReader(const SewerMap& map, const std::string& file, Diagnostics& diagnostics)
      : map_(map), file_(file), diagnostics_(diagnostics) {}

  void error(const std::string& path, std::string message) {
    diagnostics_.error(file_ + ":" + path, std::move(message));
  }

  // The members of `object` at `path`, each known; false if it is not an object.
  bool object(const json& object, const std::string& path,
              std::initializer_list<std::string_view> known) {
    if (!object.is_object()) {
      error(path, "expected an object");
      return false;
    }
    for (const auto& item : object.items()) {
      bool is_known = false;
      for (std::string_view k : known) is_known = is_known || item.key() == k;
      if (!is_known) error(path + "." + item.key(), "unknown field");
    }
    return true;
  }

  std::optional<PipeId> pipe(const json& object, const std::string& path) {
    const std::string where = path + ".pipe";
    if (!object.contains("pipe") || !object["pipe"].is_string()) {
      error(where, "expected a pipe name");
      return std::nullopt;
    }
    const std::string name = object["pipe"].get<std::string>();
    if (auto id = map_.find_pipe(name)) return id;
    error(where, "unknown pipe \"" + name + "\"");
    return std::nullopt;
  }

  std::optional<Blockage> in_pipe(const json& object, const std::string& path) {
    if (!this->object(object, path, {"pipe", "offset_m"})) return std::nullopt;
    const auto p = pipe(object, path);
    if (!p) return std::nullopt;
    const Pipe& pipe = map_.pipe(*p);
    if (!object.contains("offset_m") || !object["offset_m"].is_number() ||
        !std::isfinite(object["offset_m"].get<double>()) || object["offset_m"].get<double>() < 0 ||
        object["offset_m"].get<double>() > pipe.length_m) {
      error(path + ".offset_m", "expected an offset from 0 to " + json(pipe.length_m).dump() +
                                    " m (the length of pipe " + pipe.name + ")");
      return std::nullopt;
    }
    return Blockage{*p, object["offset_m"].get<double>()};
  }

  std::optional<ClosedPassage> passage(const json& object, const std::string& path) {
    if (!this->object(object, path, {"manhole", "from_slot", "to_slot"})) return std::nullopt;
    if (!object.contains("manhole") || !object["manhole"].is_string()) {
      error(path + ".manhole", "expected a manhole name");
      return std::nullopt;
    }
    const std::string name = object["manhole"].get<std::string>();
    const auto m = map_.find_manhole(name);
    if (!m) {
      error(path + ".manhole", "unknown manhole \"" + name + "\"");
      return std::nullopt;
    }
    const std::size_t slots = map_.slots(*m).size();
    auto slot = [&](const char* key) -> std::optional<SlotIndex> {
      const auto& v = object.contains(key) ? object[key] : json();
      if (!v.is_number_integer() || v.get<long long>() < 1 ||
          v.get<long long>() > static_cast<long long>(slots)) {
        error(path + "." + key,
              "expected a slot of manhole " + name + " from 1 to " + std::to_string(slots));
        return std::nullopt;
      }
      return SlotIndex{static_cast<std::uint16_t>(v.get<long long>() - 1)};
    };
    const auto from = slot("from_slot");
    const auto to = slot("to_slot");
    if (!from || !to) return std::nullopt;
    if (*from == *to) {
      error(path + ".to_slot", "a passage from a slot to itself");
      return std::nullopt;
    }
    return ClosedPassage{*m, *from, *to};
  }

  template <class T, class Read>
  void each(const json& root, const char* key, std::vector<T>& out, Read read) {
    if (!root.contains(key)) return;
    const std::string path = std::string("$.") + key;
    if (!root[key].is_array()) {
      error(path, "expected an array");
      return;
    }
    for (std::size_t i = 0; i < root[key].size(); ++i) {
      if (auto v = read(root[key][i], path + "[" + std::to_string(i) + "]")) out.push_back(*v);
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
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    report_json_syntax_error(text, file_name, e.byte, e.what(), diagnostics);
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  } catch (const json::exception& e) {
    diagnostics.error(file_name, std::string("JSON error: ") + e.what());
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  }
  LearntReader reader(map, file_name, diagnostics);
  if (!reader.object(root, "$", {"format", "version", "blockages", "danger", "closed_passages"})) {
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  }
  if (!root.contains("format") || root["format"] != std::string(kLearntJsonFormat)) {
    reader.error("$.format", "expected \"" + std::string(kLearntJsonFormat) + "\"");
  }
  if (!root.contains("version") || root["version"] != kLearntJsonVersion) {
    reader.error("$.version", "expected " + std::to_string(kLearntJsonVersion));
  }
  Learnt learnt;
  const auto in_pipe = [&](const json& j, const std::string& path) {
    return reader.in_pipe(j, path);
  };
  reader.each(root, "blockages", learnt.blockages, in_pipe);
  reader.each(root, "danger", learnt.danger_spots, in_pipe);
  reader.each(root, "closed_passages", learnt.closed_passages,
              [&](const json& j, const std::string& path) { return reader.passage(j, path); });
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
