// SPDX-License-Identifier: MIT
// The learnt-knowledge file (docs/executor.md): read through core's JSON reader (json_fields.h),
// as every file of sewerplan is; written with nlohmann::json. Unlike hand-written files, an
// unknown field is an error here: sewerplan writes these files itself.
#include "sewerplan/executor/learnt.h"

#include <cmath>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "sewerplan/core/enum_names.h"
#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/text_file.h"

namespace sewerplan::executor {
namespace {

// A pipe's end as "from_end" names it (the map's names): 0 or 1.
constexpr detail::EnumNames<std::uint8_t, 2> kPipeEnds{{{0, "from"}, {1, "to"}}};
static_assert(detail::distinct(kPipeEnds));

using json = nlohmann::ordered_json;
using Need = JsonFields::Need;

// Passes beyond this are no robot's (and a double holds every whole number up to it exactly).
constexpr std::uint64_t kMaxPasses = std::uint64_t{1} << 53;
// Sightings of one junction beyond this are no robot's (and fit an int).
constexpr std::uint64_t kMaxSightings = 1'000'000;

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
    return in_pipe_fields(f);
  }

  // "pipe" and "offset_m" of `f`: a known pipe and an offset within it.
  std::optional<Blockage> in_pipe_fields(JsonFields& f) {
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

  std::optional<HazardBelief> hazard(JsonElement element, const std::string& path) {
    JsonFields f(element, path, file_, diagnostics_);
    f.reject_unknown({"pipe", "offset_m", "reason", "probability", "passes", "blocked"});
    const std::optional<Blockage> at = in_pipe_fields(f);
    const std::optional<std::string> reason = f.string("reason");
    const std::optional<double> probability = f.number("probability");
    const std::optional<std::uint64_t> passes = f.count("passes", kMaxPasses);
    const std::optional<bool> blocked = f.boolean("blocked");
    if (!at || !reason || !probability || !passes || !blocked) return std::nullopt;
    if (!(*probability >= 0 && *probability <= 1)) {
      f.error("probability",
              "expected a probability from 0 to 1, got " + json(*probability).dump());
      return std::nullopt;
    }
    if (*blocked && *probability != 1) {
      f.error("probability",
              "a hazard met as a blockage has probability 1, got " + json(*probability).dump());
      return std::nullopt;
    }
    return HazardBelief{
        at->pipe, at->offset_m, *reason, *probability, static_cast<std::size_t>(*passes), *blocked};
  }

  // "from_end" of `f`: "from" or "to", the pipe's end (as the map names them) a distance in it
  // counts from: 0 or 1.
  std::optional<std::uint8_t> end(JsonFields& f) {
    const std::optional<std::string> name = f.string("from_end");
    if (!name) return std::nullopt;
    if (std::optional<std::uint8_t> e = detail::value_of(kPipeEnds, *name)) return e;
    f.error("from_end", "expected \"from\" or \"to\" (the pipe's end), got \"" + *name + "\"");
    return std::nullopt;
  }

  // A distance `key` of `f` in `pipe`: from 0 to its mapped length.
  std::optional<double> distance(JsonFields& f, std::string_view key, const Pipe& pipe) {
    const std::optional<double> d = f.number(key);
    if (!d) return std::nullopt;
    if (!std::isfinite(*d) || *d < 0 || *d > pipe.length_m) {
      f.error(key, "expected a distance from 0 to " + json(pipe.length_m).dump() +
                       " m (the length of pipe " + pipe.name + "), got " + json(*d).dump());
      return std::nullopt;
    }
    return d;
  }

  std::optional<localisation::KnownJunction> junction(JsonElement element,
                                                      const std::string& path) {
    JsonFields f(element, path, file_, diagnostics_);
    f.reject_unknown({"pipe", "from_end", "distance_m", "sd_m", "sightings"});
    const auto p = pipe(f);
    const auto from = end(f);
    if (!p || !from) return std::nullopt;
    const std::optional<double> d = distance(f, "distance_m", map_.pipe(*p));
    const std::optional<double> sd = f.number("sd_m");
    const std::optional<std::uint64_t> sightings = f.count("sightings", kMaxSightings);
    if (!d || !sd || !sightings) return std::nullopt;
    const double var = *sd * *sd;
    if (!(std::isfinite(var) && var > 0)) {
      f.error("sd_m", "expected a standard deviation above 0 m, got " + json(*sd).dump());
      return std::nullopt;
    }
    if (*sightings < 1) {
      f.error("sightings", "expected at least 1 sighting");
      return std::nullopt;
    }
    return localisation::KnownJunction{.pipe = *p,
                                       .from_end = *from,
                                       .distance_m = *d,
                                       .var_m2 = var,
                                       .sightings = static_cast<int>(*sightings)};
  }

  std::optional<localisation::KnownMouth> mouth(JsonElement element, const std::string& path) {
    JsonFields f(element, path, file_, diagnostics_);
    f.reject_unknown({"manhole", "azimuth_deg", "invert_z_m", "diameter_m", "sightings"});
    const std::optional<std::string> name = f.string("manhole");
    const std::optional<double> azimuth = f.number("azimuth_deg");
    const std::optional<double> invert = f.number("invert_z_m");
    const std::optional<double> diameter = f.number("diameter_m");
    const std::optional<std::uint64_t> sightings = f.count("sightings", kMaxSightings);
    if (!name || !azimuth || !invert || !diameter || !sightings) return std::nullopt;
    const auto m = map_.find_manhole(*name);
    if (!m) {
      f.error("manhole", "unknown manhole \"" + *name + "\"");
      return std::nullopt;
    }
    if (!(std::isfinite(*azimuth) && *azimuth >= 0 && *azimuth < 360)) {
      f.error("azimuth_deg",
              "expected a direction in [0, 360) degrees, got " + json(*azimuth).dump());
      return std::nullopt;
    }
    if (!std::isfinite(*invert)) {
      f.error("invert_z_m", "expected a height, got " + json(*invert).dump());
      return std::nullopt;
    }
    if (!(std::isfinite(*diameter) && *diameter > 0)) {
      f.error("diameter_m", "expected a size above 0 m, got " + json(*diameter).dump());
      return std::nullopt;
    }
    if (*sightings < 1) {
      f.error("sightings", "expected at least 1 sighting");
      return std::nullopt;
    }
    return localisation::KnownMouth{.manhole = *m,
                                    .azimuth_deg = *azimuth,
                                    .invert_z_m = *invert,
                                    .diameter_m = *diameter,
                                    .sightings = static_cast<int>(*sightings)};
  }

  std::optional<localisation::DrivenStretch> stretch(JsonElement element, const std::string& path) {
    JsonFields f(element, path, file_, diagnostics_);
    f.reject_unknown({"pipe", "from_end", "from_m", "to_m"});
    const auto p = pipe(f);
    const auto from = end(f);
    if (!p || !from) return std::nullopt;
    const Pipe& pipe = map_.pipe(*p);
    const std::optional<double> a = distance(f, "from_m", pipe);
    const std::optional<double> b = distance(f, "to_m", pipe);
    if (!a || !b) return std::nullopt;
    if (!(*a < *b)) {
      f.error("to_m",
              "expected more than from_m (" + json(*a).dump() + " m), got " + json(*b).dump());
      return std::nullopt;
    }
    return localisation::DrivenStretch{.pipe = *p, .from_end = *from, .from_m = *a, .to_m = *b};
  }

  template <class T, class Read>
  void each(JsonFields& parent, std::string_view key, std::vector<T>& out, Read read) {
    const std::optional<JsonArray> items = parent.array(key, Need::kOptional);
    if (!items) return;
    std::size_t i = 0;
    for (JsonElement item : *items) {
      if (auto v = read(item, indexed(parent.path() + "." + std::string(key), i++))) {
        out.push_back(*v);
      }
    }
  }

  // "junction_memory" of the root (version 3): {"junctions": [...], "driven": [...]}, and from
  // version 4 "mouths": [...].
  void memory(JsonFields& root, localisation::JunctionMemory& out, std::optional<double> version) {
    const std::optional<JsonElement> element = root.member("junction_memory", Need::kOptional);
    if (!element) return;
    JsonFields f(*element, root.path() + ".junction_memory", file_, diagnostics_);
    if (!f.is_object()) return;  // reported
    f.reject_unknown({"junctions", "driven", "mouths"});
    if (version && *version < 4 && f.has("mouths")) {
      f.error("mouths", "remembered mouths need version 4 or later");
      return;
    }
    each(f, "mouths", out.mouths,
         [&](JsonElement e, const std::string& path) { return mouth(e, path); });
    each(f, "junctions", out.junctions,
         [&](JsonElement e, const std::string& path) { return junction(e, path); });
    each(f, "driven", out.driven,
         [&](JsonElement e, const std::string& path) { return stretch(e, path); });
  }

 private:
  const SewerMap& map_;
  const std::string& file_;
  Diagnostics& diagnostics_;
};

}  // namespace

double hazard_probability_after_pass(double probability, std::size_t passes,
                                     double prior_strength) {
  if (!std::isfinite(prior_strength)) return probability;                // a prior nothing moves
  const double strength = prior_strength + static_cast<double>(passes);  // a + b
  return probability * strength / (strength + 1);
}

bool same_hazard(const HazardBelief& belief, const Hazard& hazard) {
  return belief.pipe == hazard.pipe && std::abs(belief.offset_m - hazard.offset_m) <= 1e-6 &&
         belief.reason == hazard.reason;
}

Result<void> check_hazard_belief(const HazardBelief& belief, const SewerMap& map) {
  const auto invalid = [](std::string what) -> Result<void> {
    return Error{ErrorCode::kInvalidArgument, "invalid learnt hazard: " + std::move(what)};
  };
  if (belief.pipe.index() >= map.pipe_count()) {
    return invalid("unknown pipe #" + std::to_string(belief.pipe.index()));
  }
  const Pipe& pipe = map.pipe(belief.pipe);
  std::ostringstream out;
  out << "'" << belief.reason << "' in pipe " << pipe.name << " at " << belief.offset_m << " m ";
  if (!std::isfinite(belief.offset_m) || belief.offset_m < 0 || belief.offset_m > pipe.length_m) {
    out << "is outside the pipe (0 to " << pipe.length_m << " m)";
    return invalid(out.str());
  }
  if (!(belief.probability >= 0 && belief.probability <= 1)) {
    out << "has probability " << belief.probability << ", not from 0 to 1";
    return invalid(out.str());
  }
  if (belief.blocked && belief.probability != 1) {
    out << "was met as a blockage but has probability " << belief.probability << ", not 1";
    return invalid(out.str());
  }
  return {};
}

Mission with_learnt(Mission mission, const Learnt& learnt) {
  for (Hazard& h : mission.hazards) {
    for (const HazardBelief& b : learnt.hazards) {
      if (same_hazard(b, h)) h.probability = b.probability;
    }
  }
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
  root.reject_unknown({"format", "version", "blockages", "danger", "closed_passages", "hazards",
                       "junction_memory"});
  // Absent or another value: one error each (a value of the wrong type is JsonFields' error).
  const std::optional<std::string> format = root.string("format", Need::kOptional);
  if (format ? *format != kLearntJsonFormat : !root.has("format")) {
    root.error("format", "expected \"" + std::string(kLearntJsonFormat) + "\"");
  }
  // Version 1 had no hazards; a reader of version 2 reads it as it was.
  const std::optional<double> version = root.number("version", Need::kOptional);
  if (version ? *version != 1 && *version != 2 && *version != 3 &&
                    *version != static_cast<double>(kLearntJsonVersion)
              : !root.has("version")) {
    root.error("version", "expected 1 to " + std::to_string(kLearntJsonVersion));
  } else if (version && *version == 1 && root.has("hazards")) {
    root.error("hazards", "learnt hazards need version 2 or later");
  } else if (version && *version < 3 && root.has("junction_memory")) {
    root.error("junction_memory", "a junction memory needs version 3 or later");
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
  reader.each(root, "hazards", learnt.hazards,
              [&](JsonElement e, const std::string& path) { return reader.hazard(e, path); });
  reader.memory(root, learnt.junctions, version);
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
  j["hazards"] = json::array();
  for (const HazardBelief& h : learnt.hazards) {
    j["hazards"].push_back({{"pipe", map.pipe(h.pipe).name},
                            {"offset_m", h.offset_m},
                            {"reason", h.reason},
                            {"probability", h.probability},
                            {"passes", h.passes},
                            {"blocked", h.blocked}});
  }
  const auto end_name = [](std::uint8_t end) { return detail::name_of(kPipeEnds, end); };
  json memory = {{"junctions", json::array()}, {"driven", json::array()}};
  for (const localisation::KnownJunction& k : learnt.junctions.junctions) {
    memory["junctions"].push_back({{"pipe", map.pipe(k.pipe).name},
                                   {"from_end", end_name(k.from_end)},
                                   {"distance_m", k.distance_m},
                                   {"sd_m", std::sqrt(k.var_m2)},
                                   {"sightings", k.sightings}});
  }
  for (const localisation::DrivenStretch& s : learnt.junctions.driven) {
    memory["driven"].push_back({{"pipe", map.pipe(s.pipe).name},
                                {"from_end", end_name(s.from_end)},
                                {"from_m", s.from_m},
                                {"to_m", s.to_m}});
  }
  memory["mouths"] = json::array();
  for (const localisation::KnownMouth& k : learnt.junctions.mouths) {
    memory["mouths"].push_back({{"manhole", map.manhole(k.manhole).name},
                                {"azimuth_deg", k.azimuth_deg},
                                {"invert_z_m", k.invert_z_m},
                                {"diameter_m", k.diameter_m},
                                {"sightings", k.sightings}});
  }
  j["junction_memory"] = std::move(memory);
  return j.dump(2) + "\n";
}

}  // namespace sewerplan::executor
