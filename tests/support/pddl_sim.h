// SPDX-License-Identifier: MIT
// A small interpreter for the typed STRIPS that export_pddl writes, for tests: it reads a domain
// and a problem, applies ground actions ("DRIVE_PIPE_TO_MANHOLE P12 M2") with PDDL's semantics
// (typed parameters, positive preconditions, delete-then-add effects; numeric effects ignored)
// and tells whether the goal holds. It checks the export against native plans without FF or
// Fast Downward; it is not a planner.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace sewerplan::testing {

class PddlSim {
 public:
  // Throws std::runtime_error on text it cannot read.
  PddlSim(const std::string& domain, const std::string& problem);

  // Applies the action (names in any case); an error says why it is not applicable.
  std::optional<std::string> apply(const std::string& action, const std::vector<std::string>& args);
  bool goal_reached() const;
  bool holds(const std::string& atom) const { return state_.count(atom) != 0; }  // "(in-pipe p6)"
  const std::set<std::string>& state() const { return state_; }

 private:
  struct Action {
    std::vector<std::pair<std::string, std::string>> parameters;  // name, type
    std::vector<std::vector<std::string>> pre, add, del;          // atoms as token lists
  };
  bool is_a(const std::string& object, const std::string& type) const;

  std::map<std::string, std::string> parent_type_;
  std::map<std::string, std::string> object_type_;
  std::map<std::string, Action> actions_;
  std::set<std::string> state_;
  std::vector<std::string> goal_;
};

}  // namespace sewerplan::testing
