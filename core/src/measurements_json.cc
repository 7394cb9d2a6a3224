// SPDX-License-Identifier: MIT
// The measurements file and the discrepancy report (measurements_json.h): read through core's JSON
// reader (json_fields.h), written with nlohmann::json.
#include "sewerplan/core/measurements_json.h"

#include <cmath>
#include <optional>

#include <nlohmann/json.hpp>

#include "sewerplan/core/json_fields.h"
#include "sewerplan/core/text_file.h"

namespace sewerplan {
namespace {

using json = nlohmann::ordered_json;
using Need = JsonFields::Need;

class Reader {
 public:
  Reader(const SewerMap& map, const std::string& file, Diagnostics& diagnostics)
      : map_(map), file_(file), d_(diagnostics) {}

  void read(JsonFields& root, MapMeasurements& out) {
    read_map(root, out);
    each(root, "sources", [&](JsonFields& f) {
      f.reject_unknown({"robot", "mission", "date"});
      MeasurementSource s;
      s.robot = f.string("robot").value_or("");
      s.mission = f.string("mission").value_or("");
      s.date = f.string("date").value_or("");
      out.sources.push_back(std::move(s));
    });
    sources_ = out.sources.size();
    if (sources_ == 0) root.error("sources", "expected at least one source");
    each(root, "pipes", [&](JsonFields& f) {
      f.reject_unknown({"pipe", "length_m", "variance_m2", "count", "sources"});
      const auto pipe = pipe_of(f);
      const auto length = positive(f, "length_m");
      const auto variance = positive(f, "variance_m2");
      const auto count = f.count("count", 1u << 31);
      SourceList sources = source_list(f);
      if (count && *count == 0) f.error("count", "expected at least 1 measurement");
      if (!pipe || !length || !variance || !count || *count == 0) return;
      if (!out.pipes.empty() && !(out.pipes.back().pipe < *pipe)) {
        f.error("pipe", "pipes must be listed once each, in the map's order");
        return;
      }
      out.pipes.push_back(
          {*pipe, {*length, *variance, static_cast<std::uint32_t>(*count)}, std::move(sources)});
    });
    each(root, "manholes", [&](JsonFields& f) { manhole(f, out); });
    each(root, "junctions", [&](JsonFields& f) {
      f.reject_unknown({"pipe", "offset_m", "sigma_m", "source", "signature"});
      const auto pipe = pipe_of(f);
      const auto offset = offset_in(f, pipe);
      const auto sigma = positive(f, "sigma_m");
      const auto source = source_of(f, "source");
      const auto sig = signature(f, "signature");
      if (pipe && offset && sigma && source && sig) {
        out.junctions.push_back({*pipe, *offset, *sigma, *sig, *source});
      }
    });
    each(root, "discrepancies", [&](JsonFields& f) { discrepancy(f, out); });
  }

 private:
  void read_map(JsonFields& root, MapMeasurements& out) {
    const std::optional<JsonElement> m = root.member("map");
    if (!m) return;
    JsonFields f(*m, "$.map", file_, d_);
    f.reject_unknown({"name", "fingerprint"});
    out.map_name = f.string("name").value_or("");
    out.map_fingerprint = f.string("fingerprint").value_or("");
    const std::string mine = map_geometry_fingerprint_of();
    if (f.has("fingerprint") && out.map_fingerprint != mine) {
      f.error("fingerprint", "these measurements are of map '" + out.map_name + "' (fingerprint " +
                                 out.map_fingerprint + "), not of map '" + map_.name() +
                                 "' (fingerprint " + mine + ")");
    }
  }

  std::string map_geometry_fingerprint_of();

  template <class Read>
  void each(JsonFields& parent, std::string_view key, Read read) {
    const std::optional<JsonArray> items = parent.array(key, Need::kOptional);
    if (!items) return;
    std::size_t i = 0;
    for (JsonElement item : *items) {
      JsonFields f(item, indexed(parent.path() + "." + std::string(key), i++), file_, d_);
      if (f.is_object()) read(f);
    }
  }

  std::optional<double> finite(JsonFields& f, std::string_view key, Need need = Need::kRequired) {
    const std::optional<double> v = f.number(key, need);
    if (v && !std::isfinite(*v)) {
      f.error(key, "expected a finite number");
      return std::nullopt;
    }
    return v;
  }

  std::optional<double> positive(JsonFields& f, std::string_view key) {
    const std::optional<double> v = finite(f, key);
    if (v && *v <= 0) {
      f.error(key, "expected a number > 0, got " + format_double(*v));
      return std::nullopt;
    }
    return v;
  }

  std::optional<PipeId> pipe_of(JsonFields& f, Need need = Need::kRequired) {
    const std::optional<std::string> name = f.string("pipe", need);
    if (!name) return std::nullopt;
    if (auto id = map_.find_pipe(*name)) return id;
    f.error("pipe", "unknown pipe \"" + *name + "\"");
    return std::nullopt;
  }

  std::optional<ManholeId> manhole_of(JsonFields& f, Need need = Need::kRequired) {
    const std::optional<std::string> name = f.string("manhole", need);
    if (!name) return std::nullopt;
    if (auto id = map_.find_manhole(*name)) return id;
    f.error("manhole", "unknown manhole \"" + *name + "\"");
    return std::nullopt;
  }

  std::optional<SlotIndex> slot_of(JsonFields& f, std::string_view key, ManholeId m,
                                   Need need = Need::kRequired) {
    const std::size_t slots = map_.slots(m).size();
    const std::optional<std::uint64_t> v = f.count(key, slots, need);
    if (!v) return std::nullopt;
    if (*v < 1) {
      f.error(key, "expected a slot of manhole " + map_.manhole(m).name + " from 1 to " +
                       std::to_string(slots));
      return std::nullopt;
    }
    return SlotIndex{static_cast<std::uint16_t>(*v - 1)};
  }

  std::optional<double> offset_in(JsonFields& f, std::optional<PipeId> pipe) {
    const std::optional<double> v = finite(f, "offset_m");
    if (!v || !pipe) return std::nullopt;
    const Pipe& p = map_.pipe(*pipe);
    if (*v < 0 || *v > p.length_m) {
      f.error("offset_m", "expected an offset from 0 to " + format_double(p.length_m) +
                              " m (the length of pipe " + p.name + ")");
      return std::nullopt;
    }
    return v;
  }

  std::optional<std::uint32_t> source_of(JsonFields& f, std::string_view key) {
    const std::optional<std::uint64_t> v = f.count(key, 1u << 31);
    if (!v) return std::nullopt;
    if (*v >= sources_) {
      f.error(key, "expected an index into $.sources, from 0 to " +
                       std::to_string(sources_ == 0 ? 0 : sources_ - 1));
      return std::nullopt;
    }
    return static_cast<std::uint32_t>(*v);
  }

  SourceList source_list(JsonFields& f) {
    SourceList list;
    const std::optional<JsonArray> items = f.array("sources");
    if (!items) return list;
    std::size_t i = 0;
    for (JsonElement item : *items) {
      const std::string where = f.where("sources") + "[" + std::to_string(i++) + "]";
      std::uint64_t v = 0;
      if (item.get_uint64().get(v) != simdjson::SUCCESS || v >= sources_) {
        d_.error(where, "expected an index into $.sources, got " + describe_json(item));
        continue;
      }
      if (!list.empty() && v <= list.back()) {
        d_.error(where, "source indices must be ascending, each once");
        continue;
      }
      list.push_back(static_cast<std::uint32_t>(v));
    }
    return list;
  }

  std::optional<ManholeSignature> signature(JsonFields& parent, std::string_view key) {
    const std::optional<JsonElement> e = parent.member(key);
    if (!e) return std::nullopt;
    JsonFields f(*e, parent.path() + "." + std::string(key), file_, d_);
    if (!f.is_object()) return std::nullopt;
    f.reject_unknown({"shaft_diameter_m", "slots"});
    ManholeSignature s;
    bool ok = true;
    if (auto shaft = finite(f, "shaft_diameter_m"))
      s.shaft_diameter_m = *shaft;
    else
      ok = false;
    each(f, "slots", [&](JsonFields& slot) {
      slot.reject_unknown({"direction_deg", "step_m", "diameter_m"});
      const auto direction = finite(slot, "direction_deg");
      const auto step = finite(slot, "step_m");
      const auto diameter = finite(slot, "diameter_m");
      if (!direction || !step || !diameter) {
        ok = false;
        return;
      }
      s.slots.push_back({*direction, *step, *diameter});
    });
    if (!f.has("slots")) ok = false;
    if (!ok) return std::nullopt;
    if (Result<void> checked = check_signature(s); !checked.has_value()) {
      f.error("", checked.error().message);
      return std::nullopt;
    }
    return s;
  }

  void manhole(JsonFields& f, MapMeasurements& out) {
    f.reject_unknown({"manhole", "position", "observations", "turns", "sources"});
    const auto m = manhole_of(f);
    SourceList sources = source_list(f);
    if (!m) return;
    ManholeMeasurement mm{.manhole = *m, .sources = std::move(sources)};
    if (const auto p = f.member("position", Need::kOptional)) {
      JsonFields pf(*p, f.path() + ".position", file_, d_);
      pf.reject_unknown({"x_m", "y_m", "variance_m2", "count"});
      const auto x = finite(pf, "x_m");
      const auto y = finite(pf, "y_m");
      const auto variance = positive(pf, "variance_m2");
      const auto count = pf.count("count", 1u << 31);
      if (count && *count == 0) pf.error("count", "expected at least 1 measurement");
      if (x && y && variance && count && *count > 0) {
        const auto n = static_cast<std::uint32_t>(*count);
        mm.position = PositionEstimate{{*x, *variance, n}, {*y, *variance, n}};
      }
    }
    each(f, "observations", [&](JsonFields& o) {
      o.reject_unknown({"arrival_slot", "source", "signature"});
      const auto arrival = slot_of(o, "arrival_slot", *m);
      const auto source = source_of(o, "source");
      const auto sig = signature(o, "signature");
      if (arrival && source && sig) mm.observations.push_back({*arrival, *sig, *source});
    });
    each(f, "turns", [&](JsonFields& t) {
      t.reject_unknown({"from_slot", "to_slot", "direction_deg", "sigma_deg", "source"});
      const auto from = slot_of(t, "from_slot", *m);
      const auto to = slot_of(t, "to_slot", *m);
      const auto direction = finite(t, "direction_deg");
      const auto sigma = positive(t, "sigma_deg");
      const auto source = source_of(t, "source");
      if (direction && (*direction < 0 || *direction >= 360)) {
        t.error("direction_deg", "expected a direction in [0, 360)");
        return;
      }
      if (from && to && *from == *to) {
        t.error("to_slot", "a turn leaves by another slot than it came from");
        return;
      }
      if (from && to && direction && sigma && source) {
        mm.turns.push_back({*from, *to, *direction, *sigma, *source});
      }
    });
    if (!out.manholes.empty() && !(out.manholes.back().manhole < *m)) {
      f.error("manhole", "manholes must be listed once each, in the map's order");
      return;
    }
    out.manholes.push_back(std::move(mm));
  }

  void discrepancy(JsonFields& f, MapMeasurements& out) {
    f.reject_unknown({"kind", "pipe", "manhole", "slot", "or_slot", "offset_m", "value",
                      "map_value", "sigma", "sources", "description"});
    const std::optional<std::string> kind_name = f.string("kind");
    std::optional<Discrepancy::Kind> kind;
    if (kind_name) {
      kind = parse_discrepancy_kind(*kind_name);
      if (!kind) f.error("kind", "unknown discrepancy kind \"" + *kind_name + "\"");
    }
    (void)f.string("description", Need::kOptional);
    Discrepancy d;
    bool ok = kind.has_value();
    if (kind) d.kind = *kind;
    d.pipe = f.has("pipe") ? pipe_of(f) : std::nullopt;
    d.manhole = f.has("manhole") ? manhole_of(f) : std::nullopt;
    if (f.has("slot")) {
      if (d.manhole)
        d.slot = slot_of(f, "slot", *d.manhole);
      else
        f.error("slot", "a slot needs its manhole");
    }
    if (f.has("or_slot")) {
      if (!d.manhole || !d.slot || d.kind != Discrepancy::Kind::kDirectionOff) {
        f.error("or_slot", "only a direction-off with its manhole and slot has an or_slot");
      } else {
        d.or_slot = slot_of(f, "or_slot", *d.manhole);
        if (d.or_slot == d.slot) f.error("or_slot", "is the slot itself");
      }
    }
    ok = ok && f.has("pipe") == d.pipe.has_value() && f.has("manhole") == d.manhole.has_value() &&
         f.has("slot") == d.slot.has_value() && f.has("or_slot") == d.or_slot.has_value() &&
         (!d.or_slot || d.or_slot != d.slot);
    if (f.has("offset_m")) {
      if (auto v = finite(f, "offset_m"))
        d.offset_m = *v;
      else
        ok = false;
    }
    for (auto [key, value] : {std::pair{"value", &d.value}, std::pair{"map_value", &d.map_value},
                              std::pair{"sigma", &d.sigma}}) {
      if (auto v = finite(f, key))
        *value = *v;
      else
        ok = false;
    }
    SourceList sources = source_list(f);
    if (ok) out.discrepancies.push_back({d, std::move(sources)});
  }

  const SewerMap& map_;
  const std::string& file_;
  Diagnostics& d_;
  std::size_t sources_ = 0;
  std::optional<std::string> fingerprint_;
};

std::string Reader::map_geometry_fingerprint_of() {
  if (!fingerprint_) fingerprint_ = measurements_of(map_, {}).map_fingerprint;
  return *fingerprint_;
}

json signature_json(const ManholeSignature& s) {
  json slots = json::array();
  for (const SlotSighting& slot : s.slots) {
    slots.push_back({{"direction_deg", slot.relative_deg},
                     {"step_m", slot.step_m},
                     {"diameter_m", slot.diameter_m}});
  }
  return {{"shaft_diameter_m", s.shaft_diameter_m}, {"slots", std::move(slots)}};
}

json discrepancy_json(const FoundDiscrepancy& f, const SewerMap& map) {
  const Discrepancy& d = f.discrepancy;
  json j;
  j["kind"] = std::string(to_string(d.kind));
  if (d.pipe) j["pipe"] = map.pipe(*d.pipe).name;
  if (d.manhole) j["manhole"] = map.manhole(*d.manhole).name;
  if (d.slot) j["slot"] = to_paper_number(*d.slot);
  if (d.or_slot) j["or_slot"] = to_paper_number(*d.or_slot);
  if (d.kind == Discrepancy::Kind::kUnmappedJunction || d.offset_m != 0) j["offset_m"] = d.offset_m;
  j["value"] = d.value;
  j["map_value"] = d.map_value;
  j["sigma"] = d.sigma;
  j["sources"] = f.sources;
  j["description"] = describe(d, map);
  return j;
}

json head(std::string_view format, int version, const MapMeasurements& m) {
  json j;
  j["format"] = std::string(format);
  j["version"] = version;
  j["map"] = {{"name", m.map_name}, {"fingerprint", m.map_fingerprint}};
  j["sources"] = json::array();
  for (const MeasurementSource& s : m.sources) {
    j["sources"].push_back({{"robot", s.robot}, {"mission", s.mission}, {"date", s.date}});
  }
  return j;
}

}  // namespace

Result<MapMeasurements> read_measurements_json(std::string_view text, const std::string& file_name,
                                               const SewerMap& map, Diagnostics& diagnostics) {
  const Diagnostics::Mark before = diagnostics.mark();
  const std::optional<JsonDocument> doc = JsonDocument::parse(text, file_name, diagnostics);
  if (!doc) return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  JsonFields root(doc->root(), "$", file_name, diagnostics);
  if (!root.is_object()) return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  root.reject_unknown(
      {"format", "version", "map", "sources", "pipes", "manholes", "junctions", "discrepancies"});
  const std::optional<std::string> format = root.string("format", Need::kOptional);
  if (format ? *format != kMeasurementsJsonFormat : !root.has("format")) {
    root.error("format", "expected \"" + std::string(kMeasurementsJsonFormat) + "\"");
  }
  const std::optional<double> version = root.number("version", Need::kOptional);
  if (version ? *version != static_cast<double>(kMeasurementsJsonVersion) : !root.has("version")) {
    root.error("version", "expected " + std::to_string(kMeasurementsJsonVersion));
  }
  MapMeasurements out;
  Reader(map, file_name, diagnostics).read(root, out);
  if (diagnostics.has_errors_since(before))
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  return out;
}

Result<MapMeasurements> read_measurements(const std::filesystem::path& path, const SewerMap& map,
                                          Diagnostics& diagnostics) {
  Result<std::string> text = read_text_file(path);
  if (!text.has_value()) return text.error();
  return read_measurements_json(*text, path.string(), map, diagnostics);
}

std::string measurements_json(const MapMeasurements& m, const SewerMap& map) {
  json j = head(kMeasurementsJsonFormat, kMeasurementsJsonVersion, m);
  j["pipes"] = json::array();
  for (const PipeMeasurement& p : m.pipes) {
    j["pipes"].push_back({{"pipe", map.pipe(p.pipe).name},
                          {"length_m", p.length_m.mean},
                          {"variance_m2", p.length_m.variance},
                          {"count", p.length_m.count},
                          {"sources", p.sources}});
  }
  j["manholes"] = json::array();
  for (const ManholeMeasurement& mm : m.manholes) {
    json e;
    e["manhole"] = map.manhole(mm.manhole).name;
    if (mm.position) {
      e["position"] = {{"x_m", mm.position->x_m.mean},
                       {"y_m", mm.position->y_m.mean},
                       {"variance_m2", mm.position->x_m.variance},
                       {"count", mm.position->x_m.count}};
    }
    e["observations"] = json::array();
    for (const SignatureObservation& o : mm.observations) {
      e["observations"].push_back({{"arrival_slot", to_paper_number(o.arrival)},
                                   {"source", o.source},
                                   {"signature", signature_json(o.signature)}});
    }
    // Only with turns: files of robots that do not measure them read as before.
    if (!mm.turns.empty()) {
      e["turns"] = json::array();
      for (const TurnMeasurement& t : mm.turns) {
        e["turns"].push_back({{"from_slot", to_paper_number(t.from)},
                              {"to_slot", to_paper_number(t.to)},
                              {"direction_deg", t.relative_deg},
                              {"sigma_deg", t.sigma_deg},
                              {"source", t.source}});
      }
    }
    e["sources"] = mm.sources;
    j["manholes"].push_back(std::move(e));
  }
  j["junctions"] = json::array();
  for (const JunctionSighting& s : m.junctions) {
    j["junctions"].push_back({{"pipe", map.pipe(s.pipe).name},
                              {"offset_m", s.offset_m},
                              {"sigma_m", s.sigma_m},
                              {"source", s.source},
                              {"signature", signature_json(s.signature)}});
  }
  j["discrepancies"] = json::array();
  for (const FoundDiscrepancy& f : m.discrepancies)
    j["discrepancies"].push_back(discrepancy_json(f, map));
  return j.dump(2) + "\n";
}

std::string discrepancy_report_json(const CorrectedMap& corrected, const MapMeasurements& m,
                                    const SewerMap& map) {
  json j = head(kDiscrepancyReportFormat, kDiscrepancyReportVersion, m);
  j["discrepancies"] = json::array();
  for (const auto& [found, applied] : corrected.applied) {
    json d = discrepancy_json(found, map);
    d["applied"] = applied;
    j["discrepancies"].push_back(std::move(d));
  }
  return j.dump(2) + "\n";
}

}  // namespace sewerplan
