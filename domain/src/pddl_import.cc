// SPDX-License-Identifier: MIT
// import_pddl_plan: FF's and Fast Downward's plans for export_pddl, back as sewerplan plans.
//
// The plan's action lines are found (FF: the numbered steps of its output; Fast Downward: every
// line of sas_plan), their object names mapped back through PddlNames, the bookkeeping actions
// dropped, and the result given to parse_plan with the line numbers of the file, so that every
// message names the line the planner wrote.
#include <algorithm>
#include <optional>

#include "sewerplan/domain/pddl.h"
#include "sewerplan/domain/plan_text.h"

#include "object_names.h"
#include "plan_lexer.h"

namespace sewerplan::domain {
namespace {

using detail::ascii_upper;
using detail::quote_token;
using detail::split;
using detail::trim;

bool is_bookkeeping(std::string_view upper_action) {
  return upper_action == "REACH_EXIT" || upper_action == "ALL_OTHER_TASKS_DONE";
}

bool starts_with_ignoring_case(std::string_view s, std::string_view prefix) {
  return s.size() >= prefix.size() &&
         detail::equals_ignoring_case(s.substr(0, prefix.size()), prefix);
}

// FF's step line: "step    0: ACTION ARGS" or, for later steps, "        1: ACTION ARGS".
std::optional<std::string_view> ff_step(std::string_view line) {
  std::string_view rest = trim(line);
  if (starts_with_ignoring_case(rest, "step")) rest = trim(rest.substr(4));
  std::size_t digits = 0;
  while (digits < rest.size() && rest[digits] >= '0' && rest[digits] <= '9') ++digits;
  if (digits == 0 || digits >= rest.size() || rest[digits] != ':') return std::nullopt;
  return trim(rest.substr(digits + 1));
}

// What FF prints when the goal holds already: the empty plan is its plan.
bool ff_reports_empty_plan(std::string_view line) {
  return line.find("simplified to TRUE") != std::string_view::npos ||
         line.find("empty plan") != std::string_view::npos;
}

// What FF prints when it finds no plan.
bool ff_reports_failure(std::string_view line) {
  return line.find("problem proven unsolvable") != std::string_view::npos ||
         line.find("goal can be simplified to FALSE") != std::string_view::npos ||
         line.find("search space empty") != std::string_view::npos;
}

class Importer {
 public:
  Importer(const std::string& file, PddlPlanFormat format, const SewerMap& map,
           const Mission& mission, Diagnostics& diagnostics)
      : file_(file), format_(format), names_(map, mission), diagnostics_(diagnostics) {}

  // The plan as parse_plan reads it: one line per line of the input, the same line numbers.
  std::optional<std::string> translate(std::string_view text) {
    std::string out;
    std::size_t number = 0;
    bool ff_plan_started = false;
    bool ff_empty_plan = false;
    while (!text.empty()) {
      const std::size_t eol = text.find('\n');
      const std::string_view line = text.substr(0, eol);
      text = eol == std::string_view::npos ? std::string_view() : text.substr(eol + 1);
      ++number;
      if (format_ == PddlPlanFormat::kFf) {
        if (ff_reports_failure(line)) {
          failure_ = Failure{number, "FF found no plan: '" + std::string(trim(line)) + "'"};
        }
        auto step = ff_step(line);
        // FF's log has no numbered lines before the plan; after it, the first line that is
        // not a step ends the plan.
        if (step) ff_plan_started = true;
        if (ff_reports_empty_plan(line)) ff_empty_plan = true;
        if (step && !ff_plan_ended_) out += translate_action(*step, number);
        if (!step && ff_plan_started && !trim(line).empty()) ff_plan_ended_ = true;
      } else {
        out += translate_sas_line(line, number);
      }
      out += '\n';
    }
    if (format_ == PddlPlanFormat::kFf && !failure_ && !ff_plan_started && !ff_empty_plan) {
      // An empty file, or FF's log cut off before a plan (a crash, a timeout): not a plan that
      // misses the goal.
      failure_ = Failure{std::max<std::size_t>(number, 1),
                         "the file holds no FF plan: no 'step' lines and no word that the empty "
                         "plan solves the task (an empty file, or FF stopped before it found a "
                         "plan)"};
    }
    if (failure_) error(failure_->line, failure_->message);
    if (diagnostics_.error_count() > errors_before_) return std::nullopt;
    return out;
  }

 private:
  std::string translate_sas_line(std::string_view raw, std::size_t number) {
    const std::string_view line = trim(raw);
    if (line.empty() || line.front() == ';') return "";
    if (line.front() != '(' || line.back() != ')') {
      error(number,
            "expected an action in parentheses, such as '(drive_pipe_to_manhole p1 m2)', "
            "or a ';' comment; found " +
                quote_token(line));
      return "";
    }
    return translate_action(trim(line.substr(1, line.size() - 2)), number);
  }

  std::string translate_action(std::string_view action, std::size_t number) {
    const std::vector<std::string_view> tokens = split(action);
    if (tokens.empty()) {
      error(number, "an empty action");
      return "";
    }
    const std::string name = ascii_upper(tokens.front());
    if (is_bookkeeping(name)) return "";
    std::string out = name;
    for (std::size_t i = 1; i < tokens.size(); ++i) {
      auto original = names_.original(tokens[i]);
      if (!original) {
        error(number, "unknown object " + quote_token(tokens[i]) + " in " + quote_token(action) +
                          ": not a manhole, pipe or task of the exported map and mission");
        return "";
      }
      out += ' ';
      out += *original;
    }
    return out;
  }

  void error(std::size_t line, const std::string& message) {
    diagnostics_.error(file_ + ":" + std::to_string(line), message);
  }

  const std::string& file_;
  PddlPlanFormat format_;
  PddlNames names_;
  Diagnostics& diagnostics_;
  std::size_t errors_before_ = diagnostics_.error_count();
  bool ff_plan_ended_ = false;
  struct Failure {
    std::size_t line;
    std::string message;
  };
  std::optional<Failure> failure_;
};

}  // namespace

Result<Plan> import_pddl_plan(std::string_view text, const std::string& file_name,
                              PddlPlanFormat format, const SewerMap& map, const Mission& mission,
                              Diagnostics& diagnostics) {
  const Diagnostics::Mark before = diagnostics.mark();
  std::optional<std::string> translated =
      Importer(file_name, format, map, mission, diagnostics).translate(text);
  if (!translated) return Error{ErrorCode::kParse, diagnostics.error_summary(before)};
  return parse_plan(*translated, file_name, map, mission, diagnostics);
}

}  // namespace sewerplan::domain
