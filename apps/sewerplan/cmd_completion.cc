// SPDX-License-Identifier: MIT
// sewerplan completion: prints the bash completion of the command, written from the option tables
// the commands parse with (every command registered, as for --help), so that it offers exactly
// what each command accepts. It scraped each command's --help before, and offered what a help
// text mentions but the command rejects (`plan --can`, from the exit codes below every --help).
// The build writes it once, for the package (apps/CMakeLists.txt); `source <(sewerplan
// completion)` loads it by hand.
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "sewerplan/core/generator.h"
#include "sewerplan/core/robot_profile.h"
#include "sewerplan/search/heuristic.h"
#include "sewerplan/search/planner.h"

#include "command.h"

namespace sewerplan::cli {
namespace {

// The commands of `app` a reader is shown (a command in no group is hidden), in --help's order.
std::vector<const CLI::App*> shown_commands(const CLI::App& app) {
  std::vector<const CLI::App*> out;
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (!sub->get_name().empty() && !sub->get_group().empty() && !sub->get_disabled()) {
      out.push_back(sub);
    }
  }
  return out;
}

// Every name of every option `command` accepts and --help shows: "-h --help --map ...".
std::string option_words(const CLI::App& command) {
  std::string words;
  for (const CLI::Option* option : command.get_options()) {
    if (option->get_group().empty()) continue;  // hidden: the deprecated positional MAP
    for (const std::string& name : option->get_snames()) words += " -" + name;
    for (const std::string& name : option->get_lnames()) words += " --" + name;
  }
  return words.empty() ? words : words.substr(1);
}

// The names of a table as the error messages list them ("a, b, c"), as shell words ("a b c").
std::string words(std::string listed) {
  std::string out;
  for (char c : listed) {
    if (c != ',') out += c;
  }
  return out;
}

std::string joined_names(const std::vector<const CLI::App*>& commands) {
  std::string names;
  for (const CLI::App* c : commands) names += (names.empty() ? "" : " ") + c->get_name();
  return names;
}

// The part of the script that is not a table: finding the command (and its command: `campaign
// merge`) among the words, then a value for the option before the cursor, an option, a command's
// command, or a file.
// clang-format off
constexpr const char* kCompleter = R"bash(
_sewerplan() {
  local cur prev command sub i word
  cur=${COMP_WORDS[COMP_CWORD]}
  prev=${COMP_WORDS[COMP_CWORD-1]}
  command=""
  sub=""
  for ((i = 1; i < COMP_CWORD; i++)); do
    word=${COMP_WORDS[i]}
    case $word in -*) continue ;; esac
    if [ -z "$command" ]; then
      command=$word
    elif [ -z "$sub" ] && [[ " $(_sewerplan_subcommands "$command") " == *" $word "* ]]; then
      sub=$word
    fi
  done
  if [ -z "$command" ]; then
    COMPREPLY=($(compgen -W "$_sewerplan_commands $(_sewerplan_options '')" -- "$cur"))
    return
  fi
  case $prev in
    -a|--algorithm) COMPREPLY=($(compgen -W "$_sewerplan_algorithms" -- "$cur")); return ;;
    --heuristic) COMPREPLY=($(compgen -W "$_sewerplan_heuristics" -- "$cur")); return ;;
    --risk) COMPREPLY=($(compgen -W "impassable avoid expected ignore" -- "$cur")); return ;;
    --gis-fields) COMPREPLY=($(compgen -f -X '!*.json' -- "$cur") $(compgen -d -- "$cur")); return ;;
    --topology|-t) COMPREPLY=($(compgen -W "$_sewerplan_topologies" -- "$cur")); return ;;
    --to) COMPREPLY=($(compgen -W "json ascii" -- "$cur")); return ;;
    --format) COMPREPLY=($(compgen -W "ff fd" -- "$cur")); return ;;
    --profile) COMPREPLY=($(compgen -W "$_sewerplan_profiles" -- "$cur") $(compgen -f -- "$cur")); return ;;
  esac
  if [[ $cur == -* ]]; then
    COMPREPLY=($(compgen -W "$(_sewerplan_options "$command${sub:+ $sub}")" -- "$cur"))
    return
  fi
  if [ -z "$sub" ]; then
    COMPREPLY=($(compgen -W "$(_sewerplan_subcommands "$command")" -- "$cur"))
  fi
  COMPREPLY+=($(compgen -f -- "$cur"))
}
complete -o filenames -F _sewerplan sewerplan
)bash";
// clang-format on

void print_completion(const CLI::App& root, std::ostream& out) {
  out << "# SPDX-License-Identifier: MIT\n"
         "# bash completion for sewerplan, written by `sewerplan completion` from the option\n"
         "# tables its commands parse with. Installed to\n"
         "# /usr/share/bash-completion/completions/sewerplan.\n\n";
  const std::vector<const CLI::App*> commands = shown_commands(root);
  out << "_sewerplan_commands=\"" << joined_names(commands) << "\"\n";
  // The values of the options whose names come from a table the parser reads too.
  std::string profiles;
  for (const std::string& name : builtin_profile_names())
    profiles += (profiles.empty() ? "" : " ") + name;
  out << "_sewerplan_algorithms=\"" << words(search::algorithm_names()) << "\"\n"
      << "_sewerplan_heuristics=\"" << words(search::heuristic_names()) << "\"\n"
      << "_sewerplan_topologies=\"" << words(topology_names()) << "\"\n"
      << "_sewerplan_profiles=\"" << profiles << "\"\n\n";
  out << "# The options of the command (\"campaign merge\": of its command), or of none.\n"
         "_sewerplan_options() {\n  case $1 in\n";
  out << "    '') echo \"" << option_words(root) << "\" ;;\n";
  for (const CLI::App* command : commands) {
    out << "    '" << command->get_name() << "') echo \"" << option_words(*command) << "\" ;;\n";
    for (const CLI::App* sub : shown_commands(*command)) {
      out << "    '" << command->get_name() << ' ' << sub->get_name() << "') echo \""
          << option_words(*sub) << "\" ;;\n";
    }
  }
  out << "  esac\n}\n\n";
  out << "# The commands of a command.\n_sewerplan_subcommands() {\n  case $1 in\n";
  for (const CLI::App* command : commands) {
    const std::vector<const CLI::App*> subs = shown_commands(*command);
    if (!subs.empty()) {
      out << "    '" << command->get_name() << "') echo \"" << joined_names(subs) << "\" ;;\n";
    }
  }
  out << "  esac\n}\n" << kCompleter;
}

}  // namespace

void add_completion_command(CLI::App& app, Context& context) {
  CLI::App* cmd = app.add_subcommand(
      "completion",
      "Print the bash completion: the commands and each command's options (source it, or "
      "install it as bash-completion/completions/sewerplan)");
  cmd->callback([&app, &context] {
    print_completion(app, context.out);
    context.exit_code = kExitOk;
  });
}

}  // namespace sewerplan::cli
