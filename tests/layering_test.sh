#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Checks the one-way dependencies between the libraries by their includes:
#   core <- domain <- search; fusion and localisation on core and domain; hal on core; executor on all;
#   campaign on all (with executor); render on core, domain, hal and executor (the typed events of
#   the logs it draws); nothing includes campaign except apps, tests, bench, the Python module
#   (python/) and the operator station's server (server/, its campaigns) (and campaign itself); the
#   server also on render (event logs read back) and gis (its headers: the GeoJSON export's input;
#   the program gives the functions); motion (OMPL's head path planner) on fusion; modules (the
#   module loader and the modules, the programs' floor) on all, and nothing below includes it.
# And no library but modules holds loader code: no dlopen in what an embedder links.
set -euo pipefail
cd "$(dirname "$0")/.."
declare -A allowed=(
  [core]="core"
  [domain]="core domain"
  [search]="core domain search"
  [fusion]="core domain fusion"
  [hal]="core hal"
  [executor]="core domain search fusion localisation hal executor"
  [campaign]="core domain search fusion localisation hal executor campaign"
  [render]="core domain hal executor render"
  [gis]="core domain gis"
  [localisation]="core domain localisation"
  [server]="core domain search fusion localisation hal executor campaign render gis server"
  [motion]="core domain fusion motion"
  [modules]="core domain search fusion motion localisation hal executor campaign render gis server modules"
)
status=0
for lib in "${!allowed[@]}"; do
  [ -d "$lib" ] || continue
  while IFS=: read -r file line include; do
    used=$(sed -E 's|.*"sewerplan/([a-z]+)/.*|\1|' <<<"$include")
    if [[ " ${allowed[$lib]} " != *" $used "* ]]; then
      echo "$file:$line: $lib must not include sewerplan/$used (allowed: ${allowed[$lib]})"
      status=1
    fi
  done < <(grep -rnE '#include "sewerplan/[a-z]+/' "$lib" --include='*.h' --include='*.cc' || true)
done
for lib in "${!allowed[@]}"; do
  [ "$lib" = modules ] || [ ! -d "$lib" ] && continue
  if grep -rnE 'dlopen|dlsym|<dlfcn\.h>' "$lib" --include='*.h' --include='*.cc'; then
    echo "$lib: loader code (dlopen) belongs in modules/, not in a library an embedder links"
    status=1
  fi
done
[ $status -eq 0 ] && echo "layering: ok"
exit $status
