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

class ConditionReader {
 public:
  ConditionReader(const std::string& file, Diagnostics& d) : file_(file), d_(d) {}

  void run(std::span<const XmlNode> inspected, std::vector<FindingRecord>& findings,
           std::vector<XmlNode>& elements);

 private:
  std::string at(XmlNode n) const { return file_ + ":" + xml::path(n); }

  std::optional<double> number(XmlNode parent, std::string_view name, const std::string& object,
                               bool required) {
    return xml::number(parent, name, object, required, file_, d_);
  }

  std::optional<bool> against_flow(XmlNode inspection, const std::string& object);

  const std::string& file_;
  Diagnostics& d_;
  std::size_t not_pipes_ = 0;
  std::size_t without_direction_ = 0;
  std::size_t older_ = 0;
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

void ConditionReader::run(std::span<const XmlNode> inspected, std::vector<FindingRecord>& findings,
                          std::vector<XmlNode>& elements) {
  // Per object name: its latest inspection (by Inspektionsdatum; a later entry wins a tie).
  struct Latest {
    std::string date;
    XmlNode inspection;
    std::string name;
  };
  std::vector<Latest> latest;
  std::unordered_map<std::string, std::size_t> index;
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
      const std::string date(xml::text(xml::child(oi, "Inspektionsdatum")));
      auto [it, inserted] = index.emplace(name, latest.size());
      if (inserted) {
        latest.push_back({date, oi, name});
      } else {
        ++older_;
        if (date >= latest[it->second].date) latest[it->second] = {date, oi, name};
      }
    }
  }
  for (const Latest& l : latest) {
    const std::string object = "inspection of " + l.name;
    const std::optional<bool> against = against_flow(l.inspection, object);
    if (!against) continue;
    std::vector<XmlNode> records;
    collect(l.inspection, "RZustand", records);
    for (XmlNode r : records) {
      const std::string_view code = xml::text(xml::child(r, "InspektionsKode"));
      if (code.empty()) {
        d_.error(at(r), object + ": a finding without InspektionsKode");
        continue;
      }
      const std::optional<double> station = number(r, "Station", object, true);
      if (!station) continue;
      elements.push_back(r);
      findings.push_back(
          {.pipe = l.name,
           .code = std::string(code),
           .characterisation = std::string(xml::text(xml::child(r, "Charakterisierung1"))) +
                               std::string(xml::text(xml::child(r, "Charakterisierung2"))),
           .station_m = *station,
           .against_flow = *against,
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
  warn_counted(d_, file_, older_,
               "earlier inspections of an object are superseded by its latest (Inspektionsdatum)");
}

}  // namespace

void read_condition_records(std::span<const pugi::xml_node> inspected, const std::string& file,
                            Diagnostics& diagnostics, std::vector<FindingRecord>& findings,
                            std::vector<pugi::xml_node>& elements) {
  ConditionReader(file, diagnostics).run(inspected, findings, elements);
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
  detail::read_condition_records(inspected, file_name, diagnostics, findings, elements);
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
