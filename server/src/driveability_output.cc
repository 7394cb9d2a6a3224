// SPDX-License-Identifier: MIT
#include "sewerplan/server/driveability_output.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "sewerplan/core/message_text.h"

namespace sewerplan::server {
namespace {

constexpr std::size_t kListed = 8;  // names shown per line of the text report

template <class Id, class NameOf>
void print_names(const std::vector<Id>& ids, NameOf name_of, std::ostream& out) {
  for (std::size_t i = 0; i < ids.size() && i < kListed; ++i) {
    out << (i == 0 ? ": " : ", ") << name_of(ids[i]);
  }
  if (ids.size() > kListed) out << ", ...";
  out << '\n';
}

std::string describe(const domain::PassageLimit& p, const SewerMap& map,
                     const RobotProfile& profile) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << map.manhole(p.manhole).name << " "
    << to_paper_number(p.from) << "<->" << to_paper_number(p.to) << " ("
    << map.pipe(map.slot(p.manhole, p.from).pipe).name << ", "
    << map.pipe(map.slot(p.manhole, p.to).pipe).name << "):";
  if (p.turn_exceeded) {
    const LimitText t = limit_text_fixed(p.turn_deg, profile.max_turn_deg);
    s << " turn " << t.value << " deg > " << t.limit;
  }
  if (p.step_exceeded) {
    const LimitText t = limit_text_fixed(std::abs(p.step_m), profile.max_step_m);
    s << " step " << t.value << " m > " << t.limit;
  }
  if (!p.motion_reason.empty()) s << " no motion: " << p.motion_reason;
  return s.str();
}

}  // namespace

std::vector<FindingRisk> closing_findings(const SewerMap& map, const RobotProfile& profile,
                                          const RiskTable& table) {
  std::vector<FindingRisk> risks = assess_findings(map, profile, table);
  std::erase_if(risks, [](const FindingRisk& r) { return r.effect != RiskEffect::kImpassable; });
  return risks;
}

domain::DriveabilityReport analyse_profile(const SewerMap& map, const RobotProfile& profile,
                                           std::span<const ManholeId> starts,
                                           const PassageMotionTable* motion,
                                           const RiskTable& table) {
  const std::vector<Blockage> closures =
      impassable_blockages(map, assess_findings(map, profile, table));
  return domain::analyse_driveability(map, profile, starts, motion, closures);
}

namespace {

// A closing finding's pipe, when the robot could not enter it even without the findings: why;
// else empty.
std::string_view undrivable_anyway(const SewerMap& map, const FindingRisk& r,
                                   const domain::DriveabilityReport& report) {
  const std::string_view why = domain::why_not_driveable(map.findings()[r.finding].pipe, report);
  return why == "cut off by a closure" ? std::string_view() : why;
}

}  // namespace

Closures split_closures(const SewerMap& map, const RobotProfile& profile, const RiskTable& table,
                        const domain::DriveabilityReport& report) {
  Closures c;
  for (FindingRisk& r : closing_findings(map, profile, table)) {
    const std::string_view why = undrivable_anyway(map, r, report);
    if (why.empty()) {
      c.enterable.push_back(std::move(r));
    } else {
      c.undrivable.emplace_back(std::move(r), why);
    }
  }
  return c;
}

nlohmann::json closures_json(const SewerMap& map, const Closures& closed) {
  auto entry = [&](const FindingRisk& r) {
    const Finding& f = map.findings()[r.finding];
    return nlohmann::json{{"pipe", map.pipe(f.pipe).name},
                          {"offset_m", f.offset_m},
                          {"code", f.code},
                          {"reason", r.reason}};
  };
  nlohmann::json enterable = nlohmann::json::array();
  for (const FindingRisk& r : closed.enterable) enterable.push_back(entry(r));
  nlohmann::json undrivable = nlohmann::json::array();
  for (const auto& [r, why] : closed.undrivable) {
    nlohmann::json e = entry(r);
    e["pipe_not_driveable"] = why;
    undrivable.push_back(std::move(e));
  }
  return {{"closed_by_findings", std::move(enterable)},
          {"closed_by_findings_in_undrivable_pipes", std::move(undrivable)}};
}

void print_driveability(const domain::DriveabilityReport& r, const SewerMap& map,
                        const RobotProfile& profile, std::ostream& out) {
  auto pipe_name = [&](PipeId p) { return map.pipe(p).name; };
  auto manhole_name = [&](ManholeId m) { return map.manhole(m).name; };
  out << std::fixed << std::setprecision(2) << "profile        " << profile.name << " (pipes "
      << profile.min_pipe_diameter_m << " to " << profile.max_pipe_diameter_m << " m, steps up to "
      << profile.max_step_m << " m, turns up to " << profile.max_turn_deg << " deg)\n";
  out << "too narrow     " << r.too_narrow.size() << " pipes";
  print_names(r.too_narrow, pipe_name, out);
  out << "too wide       " << r.too_wide.size() << " pipes";
  print_names(r.too_wide, pipe_name, out);
  out << "passages       " << r.passages.size() << " of " << r.passages_checked
      << " beyond the turn or step limit\n";
  for (std::size_t i = 0; i < r.passages.size() && i < kListed; ++i) {
    out << "               " << describe(r.passages[i], map, profile) << '\n';
  }
  if (r.passages.size() > kListed) out << "               ...\n";
  double total_m = 0;
  for (const Pipe& p : map.pipes()) total_m += p.length_m;
  out << "reachable      " << r.reachable_manholes.size() << " of " << map.manhole_count()
      << " manholes, " << r.reachable_pipes.size() << " of " << map.pipe_count() << " pipes ("
      << r.reachable_length_m << " of " << total_m << " m) from " << r.starts.size()
      << (r.starts.size() == 1 ? " start" : " starts");
  print_names(r.starts, manhole_name, out);
  if (r.closures.empty()) return;
  out << "cut off        " << r.cut_off_manholes.size() << " manholes, " << r.cut_off_pipes.size()
      << " pipes by " << r.closures.size() << " places closed by findings";
  print_names(r.cut_off_pipes, pipe_name, out);
}

nlohmann::json driveability_json(const domain::DriveabilityReport& r, const SewerMap& map,
                                 const RobotProfile& profile) {
  auto pipe_names = [&](const std::vector<PipeId>& ids) {
    nlohmann::json list = nlohmann::json::array();
    for (PipeId p : ids) list.push_back(map.pipe(p).name);
    return list;
  };
  auto manhole_names = [&](const std::vector<ManholeId>& ids) {
    nlohmann::json list = nlohmann::json::array();
    for (ManholeId m : ids) list.push_back(map.manhole(m).name);
    return list;
  };
  nlohmann::json passages = nlohmann::json::array();
  for (const domain::PassageLimit& p : r.passages) {
    passages.push_back({{"manhole", map.manhole(p.manhole).name},
                        {"from_slot", to_paper_number(p.from)},
                        {"to_slot", to_paper_number(p.to)},
                        {"from_pipe", map.pipe(map.slot(p.manhole, p.from).pipe).name},
                        {"to_pipe", map.pipe(map.slot(p.manhole, p.to).pipe).name},
                        {"turn_deg", p.turn_deg},
                        {"step_m", p.step_m},
                        {"turn_exceeded", p.turn_exceeded},
                        {"step_exceeded", p.step_exceeded}});
    if (!p.motion_reason.empty()) passages.back()["motion_reason"] = p.motion_reason;
  }
  return {{"profile", profile.name},
          {"too_narrow", pipe_names(r.too_narrow)},
          {"too_wide", pipe_names(r.too_wide)},
          {"passages_checked", r.passages_checked},
          {"passages", passages},
          {"starts", manhole_names(r.starts)},
          {"reachable",
           {{"manholes", manhole_names(r.reachable_manholes)},
            {"pipes", pipe_names(r.reachable_pipes)},
            {"length_m", r.reachable_length_m}}},
          {"cut_off_by_findings",
           {{"closures", r.closures.size()},
            {"manholes", manhole_names(r.cut_off_manholes)},
            {"pipes", pipe_names(r.cut_off_pipes)}}}};
}

}  // namespace sewerplan::server
