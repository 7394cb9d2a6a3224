#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The Debian packages (docs/packaging.md): `cpack -G DEB` in the release tree builds sewerplan (the
# runtime), sewerplan-dev and, with the Python module (SEWERPLAN_PYTHON), python3-sewerplan. Checked:
#   - each holds what it should and nothing of the others' (headers, static libraries, the CMake
#     package and sewerplan.pc only in -dev; the module only in python3-sewerplan), and its
#     copyright (machine-readable, MIT) and changelog.Debian.gz (its own version) in
#     /usr/share/doc/<package>; each description has a synopsis of its own;
#   - the runtime package's Depends, and everything they depend on in turn (apt-cache depends
#     --recurse over this machine's installed packages: what apt would install on a clean root),
#     name no -dev package and no compiler;
#   - the runtime package alone, unpacked into a scratch root (dpkg -x, never into /): --version,
#     the AIS plan from the example data it ships, GeoJSON through its GIS module, PNG through its
#     PNG module, its man page and completion, no debug info;
#   - with the Python package unpacked beside it: Debian's python3 imports the module and runs the
#     Python example on the example data;
#   - -dev alone, unpacked into a root of its own: it does not depend on sewerplan (its libraries
#     need nothing of the runtime package: cmake/SewerplanPackage.cmake), and a project outside the
#     tree builds against its CMake package (find_package(sewerplan)) and runs.
# scripts/deb-clean-root.sh installs them with apt on a clean Debian 12 root; scripts/build-deb.sh
# builds them with Debian's hardened flags and runs lintian.
# Usage: deb_test.sh BUILD_DIR SOURCE_DIR VERSION
set -euo pipefail
build=$(cd "$1" && pwd)
src=$2
version=$3
work="$build/deb-test"
rm -rf "$work"
mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
(cd "$work" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/out" > "$work/cpack.log" 2>&1) || {
  cat "$work/cpack.log"; exit 1; }
package() {  # package NAME: its file (any Debian revision of VERSION)
  local f
  f=$(ls "$work/out/$1_${version}"-*_amd64.deb 2> /dev/null) || fail "no package $1 (${version}) in: $(ls "$work/out")"
  echo "$f"
}
rt=$(package sewerplan)
dev=$(package sewerplan-dev)
debs=("$rt" "$dev")
with_python=0
if ls "$build"/python/sewerplan/_sewerplan*.so > /dev/null 2>&1; then
  with_python=1
  py_deb=$(package python3-sewerplan)
  debs+=("$py_deb")
fi
[ "$(ls "$work"/out/*.deb | wc -l)" -eq "${#debs[@]}" ] || fail "unexpected packages: $(ls "$work/out")"

# Every package: its doc files, its own version, its own synopsis.
synopses=""
for deb in "${debs[@]}"; do
  name=$(dpkg-deb --field "$deb" Package)
  pv=$(dpkg-deb --field "$deb" Version)
  echo "$(basename "$deb") ($(du -k "$deb" | cut -f1) KiB): Depends: $(dpkg-deb --field "$deb" Depends)"
  dir="$work/contents/$name"
  mkdir -p "$dir"
  dpkg-deb -x "$deb" "$dir"
  copyright="$dir/usr/share/doc/$name/copyright"
  [ -f "$copyright" ] || fail "$name has no /usr/share/doc/$name/copyright"
  head -1 "$copyright" | grep -qx 'Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/' ||
    fail "$name: copyright is not machine-readable: $(head -1 "$copyright")"
  grep -q '^License: MIT$' "$copyright" && grep -q '^ Permission is hereby granted' "$copyright" ||
    fail "$name: copyright lacks the MIT license's text"
  changelog="$dir/usr/share/doc/$name/changelog.Debian.gz"
  [ -f "$changelog" ] || fail "$name has no changelog.Debian.gz"
  zcat "$changelog" | head -1 | grep -q "^sewerplan ($pv) " || fail "$name: changelog starts '$(zcat "$changelog" | head -1)', not version $pv"
  description=$(dpkg-deb --field "$deb" Description)
  synopsis=$(head -1 <<< "$description")
  [ "$(sed -n 2p <<< "$description" | sed 's/^ //')" != "$synopsis" ] || fail "$name repeats its synopsis"
  synopses+="$synopsis"$'\n'
done
[ "$(sort <<< "$synopses" | uniq -d)" = "" ] || fail "packages share a synopsis: $synopses"

# What is where.
has() { [ -e "$work/contents/$1/$2" ] || fail "$1 lacks /$2"; }
lacks() {
  local found
  found=$(cd "$work/contents/$1" && find . \( -path "./$2" -o -path "./$2/*" \) -print -quit)
  [ -z "$found" ] || fail "$1 has $found, which belongs to another package"
}
has sewerplan usr/bin/sewerplan
has sewerplan usr/share/man/man1/sewerplan.1.gz
has sewerplan usr/share/bash-completion/completions/sewerplan
has sewerplan usr/share/doc/sewerplan/cli.md
has sewerplan usr/share/sewerplan/datasets/ais-testbed/map.json
has sewerplan usr/lib/sewerplan/sewerplan_png.so
for d in usr/include 'usr/lib/*.a' usr/lib/cmake usr/lib/pkgconfig usr/lib/python3; do lacks sewerplan "$d"; done
has sewerplan-dev usr/include/sewerplan/version.h
has sewerplan-dev usr/lib/libsewerplan_core.a
has sewerplan-dev usr/lib/cmake/sewerplan/sewerplanConfig.cmake
has sewerplan-dev usr/lib/pkgconfig/sewerplan.pc
for d in usr/bin usr/lib/sewerplan usr/share/man usr/lib/python3 usr/share/sewerplan; do lacks sewerplan-dev "$d"; done
if [ "$with_python" -eq 1 ]; then
  has python3-sewerplan usr/lib/python3/dist-packages/sewerplan/__init__.py
  has python3-sewerplan usr/share/sewerplan/examples/python/plan_ais.py
  for d in usr/bin usr/include usr/lib/sewerplan 'usr/lib/*.a' usr/share/sewerplan/datasets; do lacks python3-sewerplan "$d"; done
fi

# The runtime package's dependencies, and theirs in turn, as apt would resolve them (this machine
# has them installed, as the build needed them): no -dev package, no compiler.
depends=$(dpkg-deb --field "$rt" Depends)
grep -q 'libc6' <<< "$depends" || fail "sewerplan: no shared-library dependencies"
names=$(tr ',' '\n' <<< "$depends" | sed -e 's/|.*//' -e 's/(.*)//' -e 's/ //g')
for n in $names; do
  dpkg-query -W -f='${Status}\n' "$n" 2> /dev/null | grep -q 'install ok installed' ||
    fail "sewerplan depends on $n, which this machine lacks (apt-get install $n)"
done
# shellcheck disable=SC2086 # one argument per package name
apt-cache depends --recurse --installed --no-recommends --no-suggests --no-conflicts --no-breaks \
  --no-replaces --no-enhances $names 2> "$work/apt-cache.err" | grep -v '^ ' | sed 's/:.*//' |
  sort -u > "$work/runtime-closure.txt" || { cat "$work/apt-cache.err"; fail "apt-cache depends"; }
build_tools='-dev$|^(gcc|g\+\+|cpp|c\+\+|clang|clang\+\+|binutils)(-[0-9.]+)?$|^(clang|llvm)-|^binutils-'
found=0
grep -E -e "$build_tools" "$work/runtime-closure.txt" > "$work/runtime-build-tools.txt" || found=$?
[ "$found" -ne 2 ] || fail "grep of the dependencies"
[ "$found" -eq 1 ] || fail "installing sewerplan pulls build tools: $(tr '\n' ' ' < "$work/runtime-build-tools.txt")"
echo "sewerplan pulls $(wc -l < "$work/runtime-closure.txt") packages in all (with the base system), none -dev, no compiler"

# The runtime package alone.
root="$work/root"
dpkg -x "$rt" "$root"
sp="$root/usr/bin/sewerplan"
[ "$("$sp" --version)" = "sewerplan $version" ] || fail "sewerplan --version: $("$sp" --version)"
data="$root/usr/share/sewerplan/datasets/ais-testbed"
"$sp" plan --map "$data/map.json" --mission "$data/missions/paper.json" -q > "$work/paper.plan"
cmp "$work/paper.plan" "$data/plans/paper-corrected.plan" || fail "the installed plan differs"
# The GIS module (docs/gis.md), found from the installed executable: export-geojson loads it.
if [ -f "$build/lib/sewerplan/sewerplan_gis.so" ]; then
  test -f "$root/usr/lib/sewerplan/sewerplan_gis.so" || fail "no GIS module"
  "$sp" convert --map "$data/map.json" --crs EPSG:25832 -o "$work/crs.json" > /dev/null
  "$sp" export-geojson --map "$work/crs.json" -o "$work/net.geojson" > /dev/null
  grep -q '"FeatureCollection"' "$work/net.geojson" || fail "the installed export-geojson"
  gis_ok=", GIS module"
fi
# The PNG module (docs/cli.md, render); cairo, which only it links, is in Depends through shlibdeps.
grep -q 'libcairo2' <<< "$depends" || fail "no libcairo2 dependency"
"$sp" render --map "$data/map.json" --mission "$data/missions/paper.json" -o "$work/paper.png" > /dev/null
[ "$(head -c 8 "$work/paper.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
  fail "the installed render wrote no PNG"
if [ -x "$build/bench/sewerplan-compare" ]; then
  test -x "$root/usr/bin/sewerplan-compare" || fail "no sewerplan-compare"
fi
for f in "$sp" "$root"/usr/lib/sewerplan/*.so; do
  if objdump -h "$f" 2> /dev/null | grep -q '\.debug_info'; then fail "$f has debug info"; fi
done

# With the Python package beside it.
if [ "$with_python" -eq 1 ]; then
  dpkg -x "$py_deb" "$root"
  pydir="$root/usr/lib/python3/dist-packages"
  module=$(ls "$pydir"/sewerplan/_sewerplan*.so) || fail "no Python module"
  if objdump -h "$module" | grep -q '\.debug_info'; then fail "$module has debug info"; fi
  py_depends=$(dpkg-deb --field "$py_deb" Depends)
  grep -q 'python3 (>=' <<< "$py_depends" || fail "python3-sewerplan: no python3 dependency"
  grep -q "sewerplan (= $(dpkg-deb --field "$rt" Version))" <<< "$py_depends" ||
    fail "python3-sewerplan does not depend on its sewerplan"
  py=(env PYTHONDONTWRITEBYTECODE=1 PYTHONPATH="$pydir" /usr/bin/python3)
  out=$(cd "$work" && "${py[@]}" -c 'import sewerplan; print(sewerplan.__file__)')
  case "$out" in "$pydir"/*) ;; *) fail "imported sewerplan from $out" ;; esac
  example="$root/usr/share/sewerplan/examples/python/plan_ais.py"
  test -x "$example" || fail "no $example"
  (cd "$work" && "${py[@]}" "$example" "$data") > "$work/python.out"
  grep -q '14 steps, 585.4 s, 19.5 Wh' "$work/python.out" || {
    cat "$work/python.out"; fail "the Python example"; }
  python_ok=", Python module"
fi

# -dev alone: no dependency on the runtime package, and a program built against it runs without it
# (on the source tree's copy of the example data, which is the runtime package's).
dev_depends=$(dpkg-deb --field "$dev" Depends)
if tr ',' '\n' <<< "$dev_depends" | grep -qE '^ *sewerplan( |$)'; then
  fail "sewerplan-dev depends on sewerplan, whose files its libraries do not need: $dev_depends"
fi
dev_root="$work/dev-root"
dpkg -x "$dev" "$dev_root"
for f in "$dev_root"/usr/lib/libsewerplan_*.a; do
  if objdump -h "$f" 2> /dev/null | grep -q '\.debug_info'; then fail "$f has debug info"; fi
done
cmake -S "$src/tests/consumer" -B "$work/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$dev_root/usr" > /dev/null
cmake --build "$work/consumer" > /dev/null
out=$("$work/consumer/consumer" "$src/datasets/ais-testbed/map.json")
[ "$out" = "ais-testbed: 12 manholes, 14 pipes" ] || fail "consumer said '$out'"
echo "deb: ${#debs[@]} packages split as they should be; the runtime alone: --version, plan, PNG module${gis_ok:-}; consumer against -dev alone${python_ok:-}: ok"
