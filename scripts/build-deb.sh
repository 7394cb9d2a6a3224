#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The Debian packages as they are released (docs/packaging.md): a tree of their own, configured with
# Debian's hardened build flags (dpkg-buildflags, with DEB_BUILD_MAINT_OPTIONS=hardening=+all:
# -fstack-protector-strong, -D_FORTIFY_SOURCE=2, -Wformat -Werror=format-security, RELRO and
# BIND_NOW; PIE is the compiler's default), built without tests or benchmarks, then `cpack -G DEB`
# (sewerplan, sewerplan-dev, python3-sewerplan), then the two checks a release needs:
#   - lintian on every package: any error (E:) fails; the warnings are printed (docs/packaging.md
#     lists the ones that stay, and why);
#   - the hardening: every compile had -D_FORTIFY_SOURCE=2 and -fstack-protector-strong, and every
#     ELF file in the packages (the command, the modules, the Python extension) has them, checked by
#     hardening-check (devscripts) where installed, else readelf: a PIE executable, GNU_RELRO and
#     BIND_NOW, __stack_chk_fail; FORTIFY's *_chk imports are reported.
# Not part of the test command (a full build of its own: 47 minutes on 2 shared, loaded cores); the test
# command's install.deb checks the packages' split and contents from the release tree.
#
# Usage: scripts/build-deb.sh [--no-lint] [BUILD]    (BUILD defaults to build/deb; the packages are
# written to BUILD/packages). Installs lintian (and devscripts for hardening-check) when missing and
# run as root.
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
build=build/deb lint=1
while [ $# -gt 0 ]; do
  case "$1" in
    --no-lint) lint=0; shift ;;
    -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) echo "build-deb: unknown option $1 (--help)" >&2; exit 2 ;;
    *) build=$1; shift ;;
  esac
done
start=$(date +%s)
step() { echo "[$(($(date +%s) - start)) s] $*"; }

# The flags, as debhelper would pass them; -DNDEBUG as the release tree has it (RelWithDebInfo), and
# line tables only (-g1) for the debug information, which the packages strip anyway.
cd "$src"
export DEB_BUILD_MAINT_OPTIONS=hardening=+all
export DEB_CPPFLAGS_MAINT_APPEND=-DNDEBUG DEB_CXXFLAGS_MAINT_APPEND=-g1
cppflags=$(dpkg-buildflags --get CPPFLAGS)
cxxflags=$(dpkg-buildflags --get CXXFLAGS)
ldflags=$(dpkg-buildflags --get LDFLAGS)
launcher=()
if command -v ccache > /dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
step "configure $build: CXXFLAGS=$cppflags $cxxflags; LDFLAGS=$ldflags"
cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=None "${launcher[@]}" \
  -DCMAKE_CXX_FLAGS="$cppflags $cxxflags" -DCMAKE_EXE_LINKER_FLAGS="$ldflags" \
  -DCMAKE_SHARED_LINKER_FLAGS="$ldflags" -DCMAKE_MODULE_LINKER_FLAGS="$ldflags" \
  -DSEWERPLAN_BUILD_TESTS=OFF -DSEWERPLAN_BUILD_BENCH=OFF -DSEWERPLAN_PYTHON=ON > "$build.configure.log" ||
  { cat "$build.configure.log"; exit 1; }
build=$(cd "$build" && pwd)
step "build"
cmake --build "$build" -j "${SEWERPLAN_JOBS:-2}"

out="$build/packages"
rm -rf "$out"
step "cpack -G DEB -B $out"
(cd "$build" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$out" > "$build/cpack.log" 2>&1) || {
  cat "$build/cpack.log"; exit 1; }
debs=("$out"/*.deb)
for deb in "${debs[@]}"; do
  echo "  $(basename "$deb"): $(du -k "$deb" | cut -f1) KiB, installed $(dpkg-deb --field "$deb" Installed-Size) KiB"
done

# Hardening. Every compile had the flags: -D_FORTIFY_SOURCE=2 and -fstack-protector-strong in each
# command of compile_commands.json.
python3 - "$build/compile_commands.json" << 'PY' || exit 1
import json, sys
commands = json.load(open(sys.argv[1]))
missing = [c["file"] for c in commands
           if "-D_FORTIFY_SOURCE=2" not in c["command"] or "-fstack-protector-strong" not in c["command"]]
if missing:
    sys.exit("build-deb: FAIL: compiled without the hardening flags: " + " ".join(missing))
print(f"  all {len(commands)} compiles with -D_FORTIFY_SOURCE=2 -fstack-protector-strong")
PY
# Then every ELF file in the packages: PIE (executables), stack protector, RELRO and BIND_NOW must
# be there. FORTIFY is reported, not required: a file compiled with it whose calls all have sizes
# unknown at compile time imports only the plain functions (hardening-check's "only unprotected
# functions found"). Control-flow protection and stack-clash protection are not among Debian 12's
# flags, so not checked.
unpacked="$build/packages/unpacked"
for deb in "${debs[@]}"; do dpkg-deb -x "$deb" "$unpacked"; done
mapfile -t elves < <(find "$unpacked" -type f -exec sh -c 'head -c 4 "$1" | grep -q "^.ELF"' _ {} \; -print | sort)
[ "${#elves[@]}" -gt 0 ] || { echo "build-deb: no ELF file in the packages" >&2; exit 1; }
if ! command -v hardening-check > /dev/null && [ "$(id -u)" -eq 0 ]; then
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends devscripts > /dev/null
fi
step "hardening of ${#elves[@]} ELF files"
bad=0
for f in "${elves[@]}"; do
  name=${f#"$unpacked"}
  if command -v hardening-check > /dev/null; then
    hardening-check --quiet --nocfprotection --nofortify "$f" > /dev/null || bad=1
    hardening-check --nocfprotection "$f" | grep -v 'Control flow\|Stack clash' | sed -e "s|$unpacked||" -e 's/^/  /' || true
  else
    ok=yes
    readelf -d "$f" | grep -q 'BIND_NOW\|FLAGS.*NOW' || { echo "  $name: no BIND_NOW"; ok=NO; }
    readelf -lW "$f" | grep -q GNU_RELRO || { echo "  $name: no RELRO"; ok=NO; }
    syms=$(readelf --dyn-syms -W "$f")
    grep -q '__stack_chk_fail' <<< "$syms" || { echo "  $name: no stack protector"; ok=NO; }
    if [[ "$name" == */bin/* ]]; then
      readelf -hW "$f" | grep -q 'DYN (Position-Independent' || { echo "  $name: not PIE"; ok=NO; }
    fi
    fortify=$(grep -cE '__[a-z_]+_chk' <<< "$syms" || true)
    echo "  $name: PIE (executables), RELRO, BIND_NOW, stack protector: $ok; FORTIFY functions: $fortify"
    [ "$ok" = yes ] || bad=1
  fi
done
[ "$bad" -eq 0 ] || { echo "build-deb: FAIL: an ELF file lacks a hardening flag" >&2; exit 1; }

if [ "$lint" -eq 1 ]; then
  if ! command -v lintian > /dev/null && [ "$(id -u)" -eq 0 ]; then
    step "installing lintian"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends lintian > /dev/null
  fi
  step "lintian ${debs[*]##*/}"
  # Exit 1 on an error tag (lintian's --fail-on default); warnings are printed, and the ones that
  # stay are listed with their reasons in docs/packaging.md.
  lintian "${debs[@]}" | tee "$build/lintian.txt" || {
    echo "build-deb: FAIL: lintian reports errors ($build/lintian.txt)" >&2; exit 1; }
  echo "  lintian: $(grep -c '^E:' "$build/lintian.txt") errors, $(grep -c '^W:' "$build/lintian.txt") warnings"
fi
step "build-deb: ${#debs[@]} packages in $out"
