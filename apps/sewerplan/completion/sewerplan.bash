# SPDX-License-Identifier: MIT
# bash completion for sewerplan: the commands (kept equal to `sewerplan --help`'s list by
# tests/cli/completion_test.sh), and each command's options as its own --help prints them, so they
# never go stale. Installed to /usr/share/bash-completion/completions/sewerplan.

_sewerplan_commands="validate info generate convert plan check export-pddl import-plan simulate sim-node campaign render motion export-geojson serve merge-measurements"

_sewerplan() {
  local cur prev command i
  cur=${COMP_WORDS[COMP_CWORD]}
  prev=${COMP_WORDS[COMP_CWORD-1]}
  command=""
  for ((i = 1; i < COMP_CWORD; i++)); do
    case ${COMP_WORDS[i]} in
      -*) ;;
      *) command=${COMP_WORDS[i]}; break ;;
    esac
  done
  if [ -z "$command" ]; then
    COMPREPLY=($(compgen -W "$_sewerplan_commands --help --version" -- "$cur"))
    return
  fi
  case $prev in
    -a|--algorithm) COMPREPLY=($(compgen -W "auto astar wastar gbfs ehc exact" -- "$cur")); return ;;
    --heuristic) COMPREPLY=($(compgen -W "ff add max blind" -- "$cur")); return ;;
    --risk) COMPREPLY=($(compgen -W "impassable avoid expected ignore" -- "$cur")); return ;;
    --gis-fields) COMPREPLY=($(compgen -f -X '!*.json' -- "$cur") $(compgen -d -- "$cur")); return ;;
    --topology|-t) COMPREPLY=($(compgen -W "tree meshed" -- "$cur")); return ;;
    --to) COMPREPLY=($(compgen -W "json ascii" -- "$cur")); return ;;
    --format) COMPREPLY=($(compgen -W "ff fd" -- "$cur")); return ;;
    --profile) COMPREPLY=($(compgen -W "makro-1.1 makro-plus" -- "$cur") $(compgen -f -- "$cur")); return ;;
  esac
  case $command in
    motion) if [ "$COMP_CWORD" -eq 2 ]; then COMPREPLY=($(compgen -W "precompute" -- "$cur")); return; fi ;;
    campaign) if [ "$COMP_CWORD" -eq 2 ] && [[ $cur != -* ]]; then COMPREPLY=($(compgen -W "merge" -- "$cur")); fi ;;
  esac
  if [[ $cur == -* ]]; then
    local options
    options=$("${COMP_WORDS[0]}" "$command" --help 2>/dev/null | grep -oE -- '(^|[ ,])--?[a-zA-Z][-a-zA-Z0-9]*' | tr -d ' ,' | sort -u)
    COMPREPLY=($(compgen -W "$options" -- "$cur"))
    return
  fi
  COMPREPLY+=($(compgen -f -- "$cur"))
}
complete -o filenames -F _sewerplan sewerplan
