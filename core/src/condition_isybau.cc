// SPDX-License-Identifier: MIT
#include "condition_isybau.h"

#include <algorithm>
#include <optional>
#include <string_view>
#include <unordered_map>

#include "sewerplan/core/condition.h"
#include "sewerplan/core/text_file.h"

#include "ascii_syntax.h"
#include "network_import.h"
#include "xml_support.h"

namespace sewerplan::detail {

using XmlNode = pugi::xml_node;

// Iterative, in document order: a file nested a million levels deep must not exhaust the stack.
void collect(XmlNode node, std::string_view name, std::vector<XmlNode>& out) {
  std::vector<XmlNode> stack;
  auto push_children = [&](XmlNode n) {
    const std::size_t from = stack.size();
    for (XmlNode c = n.first_child(); c; c = c.next_sibling()) {
      if (c.type() == pugi::node_element) stack.push_back(c);
    }
    std::reverse(stack.begin() + static_cast<std::ptrdiff_t>(from), stack.end());
  };
  push_children(node);
  while (!stack.empty()) {
    const XmlNode n = stack.back();
    stack.pop_back();
    if (xml::local_name(n) == name) {
      out.push_back(n);
    } else {
      push_children(n);
    }
  }
}

namespace {

// One OptischeInspektion of a Haltung, and what it saw.
struct Inspection {
  std::string pipe;
  std::string when;  // Inspektionsdatum, "T", Uhrzeit: ISO 8601 sorts as time does
  bool against = false;
  std::size_t order = 0;  // in the file
  // The stretch it covered, from the pipe's upstream end (offsets), when the pipe's length is
  // known; else from where it began (stations), comparable only with the same direction's.
  double covered_from = 0;
  double covered_to = 0;
  std::vector<XmlNode> records;  // RZustand
  std::vector<double> stations;
  std::vector<std::string> codes;
};

class ConditionReader {
 public:
  ConditionReader(const std::string& file, Diagnostics& d, const PipeLength& pipe_length)
      : file_(file), d_(d), pipe_length_(pipe_length) {}

  void run(std::span<const XmlNode> inspected, std::vector<FindingRecord>& findings,
           std::vector<XmlNode>& elements);

 private:
  std::string at(XmlNode n) const { return file_ + ":" + xml::path(n); }

  std::optional<double> number(XmlNode parent, std::string_view name, const std::string& object,
                               bool required) {
    return xml::number(parent, name, object, required, file_, d_);
  }

  std::optional<bool> against_flow(XmlNode inspection, const std::string& object);
  std::optional<Inspection> read_inspection(XmlNode oi, const std::string& name, std::size_t order);
  // Whether `later` covered the place of finding `k` of `earlier`, and so supersedes it.
  bool supersedes(const Inspection& later, const Inspection& earlier, std::size_t k) const;
  double position(const Inspection& inspection, double station) const;

  const std::string& file_;
  Diagnostics& d_;
  const PipeLength& pipe_length_;
  std::unordered_map<std::string, std::optional<double>> lengths_;
  std::size_t not_pipes_ = 0;
  std::size_t without_direction_ = 0;
  std::size_t superseded_ = 0;
};

// "O" (or "in Fliessrichtung"): with the flow, from the upstream node; "U" (or "gegen ..."):
// against it. None given: with the flow (counted).
std::optional<bool> ConditionReader::against_flow(XmlNode inspection, const std::string& object) {
  const XmlNode n = xml::descend(inspection, {"Rohrleitung", "Inspektionsrichtung"});
  const std::string_view t = xml::text(n);
  if (t.empty()) {
    ++without_direction_;
    return false;
  }
  if (t == "O" || t == "o" || t.starts_with("in ") || t.starts_with("In ")) return false;
  if (t == "U" || t == "u" || t.starts_with("gegen") || t.starts_with("Gegen")) return true;
  d_.error(at(n), object +
                      ": Inspektionsrichtung must be O (with the flow) or U (against it), got " +
                      ascii_syntax::quoted(t));
  return std::nullopt;
}

// A station as a place on the pipe: its offset from the upstream end when the pipe's length is
// known (against the flow: the length less the station), else the station itself.
double ConditionReader::position(const Inspection& inspection, double station) const {
  const std::optional<double>& length = lengths_.at(inspection.pipe);
  return length && inspection.against ? *length - station : station;
}

std::optional<Inspection> ConditionReader::read_inspection(XmlNode oi, const std::string& name,
                                                           std::size_t order) {
  const std::string object = "inspection of " + name;
  const std::optional<bool> against = against_flow(oi, object);
  if (!against) return std::nullopt;
  Inspection inspection{.pipe = name,
                        .when = std::string(xml::text(xml::child(oi, "Inspektionsdatum"))) + "T" +
                                std::string(xml::text(xml::child(oi, "Uhrzeit"))),
                        .against = *against,
                        .order = order};
  std::vector<XmlNode> records;
  collect(oi, "RZustand", records);
  double reached = 0;
  bool at_far_end = false;  // BCE: the inspection ended at the far node
  bool abandoned = false;   // BDC: it was abandoned (a blockage, the camera could not pass)
  for (XmlNode r : records) {
    const std::string_view code = xml::text(xml::child(r, "InspektionsKode"));
    if (code.empty()) {
      d_.error(at(r), object + ": a finding without InspektionsKode");
      continue;
    }
    const std::optional<double> station = number(r, "Station", object, true);
    if (!station) continue;
    at_far_end = at_far_end || code == "BCE";
    abandoned = abandoned || code == "BDC";
    reached = std::max(reached, *station);
    inspection.records.push_back(r);
    inspection.stations.push_back(*station);
    inspection.codes.emplace_back(code);
  }
  const XmlNode rohr = xml::child(oi, "Rohrleitung");
  if (const std::optional<double> length =
          xml::optional_number(rohr, "Inspektionslaenge", object, file_, d_)) {
    reached = std::max(reached, *length);
  }
  auto [it, inserted] = lengths_.try_emplace(name);
  if (inserted) it->second = pipe_length_ ? pipe_length_(name) : std::nullopt;
  const std::optional<double>& pipe = it->second;
  if (pipe && at_far_end && !abandoned) reached = std::max(reached, *pipe);
  const double a = position(inspection, 0);
  const double b = position(inspection, reached);
  inspection.covered_from = std::min(a, b);
  inspection.covered_to = std::max(a, b);
  return inspection;
}

bool ConditionReader::supersedes(const Inspection& later, const Inspection& earlier,
                                 std::size_t k) const {
  if (later.when < earlier.when) return false;
  if (later.when == earlier.when) {
    // At the same date and time from the other end: the other half of one inspection (the
    // camera could not pass). From the same end: the same inspection written again; the later
    // entry in the file stands.
    if (later.against != earlier.against || later.order < earlier.order) return false;
  }
  if (!lengths_.at(later.pipe) && later.against != earlier.against) return false;
  constexpr double kTolerance_m = 0.01;
  const double at = position(earlier, earlier.stations[k]);
  return at >= later.covered_from - kTolerance_m && at <= later.covered_to + kTolerance_m;
}

void ConditionReader::run(std::span<const XmlNode> inspected, std::vector<FindingRecord>& findings,
                          std::vector<XmlNode>& elements) {
  // Every optical inspection of every Haltung, grouped by the Haltung's name (several entries for
  // one Haltung are one history).
  std::vector<Inspection> inspections;
  std::unordered_map<std::string, std::vector<std::size_t>> of_pipe;
  for (XmlNode object : inspected) {
    const std::string name(xml::text(xml::child(object, "Objektbezeichnung")));
    if (name.empty()) {
      d_.error(at(object), "inspected object: no Objektbezeichnung");
      continue;
    }
    const std::string_view kind = xml::text(xml::child(object, "Anlagentyp"));
    if (!kind.empty() && kind != "1") {  // 2 Anschlussleitung, 3 Schacht: not a pipe of the map
      ++not_pipes_;
      continue;
    }
    for (XmlNode oi = object.first_child(); oi; oi = oi.next_sibling()) {
      if (xml::local_name(oi) != "OptischeInspektion") continue;
      std::optional<Inspection> inspection = read_inspection(oi, name, inspections.size());
      if (!inspection) continue;
      of_pipe[name].push_back(inspections.size());
      inspections.push_back(std::move(*inspection));
    }
  }
  // A finding stands unless a later inspection covered its place: inspections from the two ends
  // complement each other, and a later one supersedes an earlier one only where it went.
  for (const Inspection& inspection : inspections) {
    const std::vector<std::size_t>& history = of_pipe.at(inspection.pipe);
    for (std::size_t k = 0; k < inspection.records.size(); ++k) {
      const bool stands = std::none_of(history.begin(), history.end(), [&](std::size_t other) {
        return other != inspection.order && supersedes(inspections[other], inspection, k);
      });
      if (!stands) {
        ++superseded_;
        continue;
      }
      const XmlNode r = inspection.records[k];
      const std::string object = "inspection of " + inspection.pipe;
      elements.push_back(r);
      findings.push_back(
          {.pipe = inspection.pipe,
           .code = inspection.codes[k],
           .characterisation = std::string(xml::text(xml::child(r, "Charakterisierung1"))) +
                               std::string(xml::text(xml::child(r, "Charakterisierung2"))),
           .station_m = inspection.stations[k],
           .against_flow = inspection.against,
           .quantity1 = number(r, "Quantifizierung1Numerisch", object, false),
           .quantity2 = number(r, "Quantifizierung2Numerisch", object, false),
           .line = static_cast<std::uint32_t>(elements.size())});
    }
  }
  warn_counted(d_, file_, not_pipes_,
               "inspected objects are laterals or manholes (Anlagentyp 2, 3): their findings are "
               "not read");
  warn_counted(d_, file_, without_direction_,
               "inspections give no Inspektionsrichtung: taken as with the flow (O)");
  warn_counted(d_, file_, superseded_,
               "findings are superseded by a later inspection (Inspektionsdatum, Uhrzeit) of the "
               "stretch they lie in");
}

}  // namespace

void read_condition_records(std::span<const pugi::xml_node> inspected, const std::string& file,
                            Diagnostics& diagnostics, const PipeLength& pipe_length,
                            std::vector<FindingRecord>& findings,
                            std::vector<pugi::xml_node>& elements) {
  ConditionReader(file, diagnostics, pipe_length).run(inspected, findings, elements);
}

}  // namespace sewerplan::detail

namespace sewerplan {

Result<SewerMap> read_condition_isybau(SewerMap map, std::string_view text,
                                       const std::string& file_name, Diagnostics& diagnostics) {
  const Diagnostics::Mark before = diagnostics.mark();
  pugi::xml_document doc;
  if (!xml::load_utf8(doc, text, file_name, diagnostics)) {
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  }
  const pugi::xml_node root = doc.document_element();
  const std::string_view name = xml::local_name(root);
  if (name != "Identifikation") {
    diagnostics.error(
        file_name + ":" + xml::path(root),
        xml::foreign_sewer_format(root).value_or("not an ISYBAU file: the root element is <" +
                                                 std::string(name) + ">, not <Identifikation>"));
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  }
  std::vector<pugi::xml_node> inspected;
  detail::collect(root, "InspizierteAbwassertechnischeAnlage", inspected);
  if (inspected.empty()) {
    diagnostics.error(file_name,
                      "no Zustandsdaten in this file (no InspizierteAbwassertechnischeAnlage)");
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  }
  std::vector<FindingRecord> findings;
  std::vector<pugi::xml_node> elements;
  const detail::PipeLength pipe_length =
      [&map](const std::string& pipe_name) -> std::optional<double> {
    const std::optional<PipeId> pipe = map.find_pipe(pipe_name);
    return pipe ? std::optional(map.pipe(*pipe).length_m) : std::nullopt;
  };
  detail::read_condition_records(inspected, file_name, diagnostics, pipe_length, findings,
                                 elements);
  if (diagnostics.has_errors_since(before)) {
    return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  }
  const Locator locate = [&](const RecordRef& ref, std::string_view) {
    return ref.line > 0 && ref.line <= elements.size()
               ? file_name + ":" + xml::path(elements[ref.line - 1])
               : file_name;
  };
  return MapBuilder::add_findings(std::move(map), std::move(findings), locate, diagnostics);
}

Result<SewerMap> read_condition(SewerMap map, const std::filesystem::path& path,
                                Diagnostics& diagnostics) {
  Result<std::string> text = read_text_file(path);
  if (!text.has_value()) return text.error();
  return read_condition_isybau(std::move(map), *text, path.string(), diagnostics);
}

}  // namespace sewerplan
