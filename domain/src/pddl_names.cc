// SPDX-License-Identifier: MIT
// PddlNames: object names as PDDL accepts them, and the way back.
#include <algorithm>

#include "sewerplan/core/ascii_case.h"
#include "sewerplan/domain/pddl.h"

namespace sewerplan::domain {
namespace {

bool is_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool is_name_char(char c) { return is_letter(c) || (c >= '0' && c <= '9') || c == '-' || c == '_'; }

bool is_pddl_name(std::string_view s) {
  return !s.empty() && is_letter(s.front()) && std::all_of(s.begin(), s.end(), is_name_char);
}

// Words the PDDL readers treat specially, which an object must not be called.
bool is_reserved(std::string_view lowered) {
  static constexpr std::string_view kReserved[] = {
      "and",    "at",     "define", "domain", "either",  "exists", "forall", "imply", "not",
      "number", "object", "or",     "over",   "problem", "start",  "end",    "when",  "all"};
  return std::find(std::begin(kReserved), std::end(kReserved), lowered) != std::end(kReserved);
}

// The name's bytes that PDDL allows, the others as '_'.
std::string sanitised(std::string_view name) {
  std::string out;
  out.reserve(name.size());
  for (char c : name) out += is_name_char(c) ? c : '_';
  return out;
}

}  // namespace

PddlNames::PddlNames(const SewerMap& map, const Mission& mission) {
  manholes_.reserve(map.manhole_count());
  for (ManholeId m : map.manhole_ids()) manholes_.push_back(claim(map.manhole(m).name, "m-"));
  pipes_.reserve(map.pipe_count());
  for (PipeId p : map.pipe_ids()) pipes_.push_back(claim(map.pipe(p).name, "p-"));
  tasks_.reserve(mission.tasks.size());
  for (const Task& t : mission.tasks) tasks_.push_back(claim(t.name, "t-"));
}

std::string PddlNames::claim(const std::string& name, std::string_view prefix) {
  if (is_pddl_name(name) && !is_reserved(ascii_lower(name)) &&
      back_.emplace(ascii_lower(name), name).second) {
    return name;
  }
  ++renamed_;
  const std::string base = std::string(prefix) + sanitised(name);
  std::string candidate = base;
  for (std::size_t n = 2; !back_.emplace(ascii_lower(candidate), name).second; ++n) {
    candidate = base + "-" + std::to_string(n);
  }
  return candidate;
}

std::optional<std::string> PddlNames::original(std::string_view pddl_name) const {
  auto found = back_.find(ascii_lower(pddl_name));
  if (found == back_.end()) return std::nullopt;
  return found->second;
}

}  // namespace sewerplan::domain
