#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The Debian package: `cpack -G DEB` in the release tree builds sewerplan_<version>_amd64.deb;
# unpacked into a scratch root (dpkg -x, never into /), its sewerplan prints the project's version
# and plans the AIS test environment from the example data it ships, writes GeoJSON through its GIS
# module (lib/sewerplan/sewerplan_gis.so, when built with GIS), its man page and bash
# completion are there, its binaries carry no debug info, its control file lists dependencies, and
# a project outside the tree builds against its CMake package (find_package(sewerplan)); with the
# Python module (SEWERPLAN_PYTHON), Debian's python3 imports it from the root's dist-packages and
# runs the Python example it installs (share/sewerplan/examples/python/plan_ais.py) on the example
# data. scripts/deb-clean-root.sh installs it with apt on a clean Debian 12 root (docs/packaging.md).
# Usage: deb_test.sh BUILD_DIR SOURCE_DIR VERSION
set -euo pipefail
build=$(cd "$1" && pwd)
src=$2
version=$3
work="$build/deb-test"
rm -rf "$work"
mkdir -p "$work"
(cd "$work" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/out" > "$work/cpack.log") || {
  cat "$work/cpack.log"; exit 1; }
deb="$work/out/sewerplan_${version}_amd64.deb"
test -f "$deb" || { echo "FAIL: no $deb"; ls "$work/out"; exit 1; }
echo "built $(basename "$deb") ($(du -k "$deb" | cut -f1) KiB)"
dpkg-deb --field "$deb" Package Version Depends
dpkg-deb --field "$deb" Depends | grep -q 'libc6' || { echo "FAIL: no shared-library dependencies"; exit 1; }
root="$work/root"
dpkg -x "$deb" "$root"
sp="$root/usr/bin/sewerplan"
[ "$("$sp" --version)" = "sewerplan $version" ] || { echo "FAIL: sewerplan --version: $("$sp" --version)"; exit 1; }
data="$root/usr/share/sewerplan/datasets/ais-testbed"
"$sp" plan --map "$data/map.json" --mission "$data/missions/paper.json" -q > "$work/paper.plan"
cmp "$work/paper.plan" "$data/plans/paper-corrected.plan" || { echo "FAIL: the installed plan differs"; exit 1; }
# The GIS module (docs/gis.md), found from the installed executable: export-geojson loads it.
if [ -f "$build/lib/sewerplan/sewerplan_gis.so" ]; then
  test -f "$root/usr/lib/sewerplan/sewerplan_gis.so" || { echo "FAIL: no GIS module"; exit 1; }
  "$sp" convert --map "$data/map.json" --crs EPSG:25832 -o "$work/crs.json" > /dev/null
  "$sp" export-geojson --map "$work/crs.json" -o "$work/net.geojson" > /dev/null
  grep -q '"FeatureCollection"' "$work/net.geojson" || { echo "FAIL: the installed export-geojson"; exit 1; }
  gis_ok=", GIS module"
fi
# The PNG module (docs/cli.md, render), found from the installed executable; cairo, which only it
# links, is in Depends through shlibdeps.
test -f "$root/usr/lib/sewerplan/sewerplan_png.so" || { echo "FAIL: no PNG module"; exit 1; }
dpkg-deb --field "$deb" Depends | grep -q 'libcairo2' || { echo "FAIL: no libcairo2 dependency"; exit 1; }
"$sp" render --map "$data/map.json" --mission "$data/missions/paper.json" -o "$work/paper.png" > /dev/null
[ "$(head -c 8 "$work/paper.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || {
  echo "FAIL: the installed render wrote no PNG"; exit 1; }
if [ -x "$build/bench/sewerplan-compare" ]; then
  test -x "$root/usr/bin/sewerplan-compare" || { echo "FAIL: no sewerplan-compare"; exit 1; }
fi
test -f "$root/usr/share/man/man1/sewerplan.1.gz" || { echo "FAIL: no man page sewerplan.1.gz"; exit 1; }
test -f "$root/usr/share/bash-completion/completions/sewerplan" || { echo "FAIL: no completion"; exit 1; }
test -f "$root/usr/share/doc/sewerplan/cli.md" || { echo "FAIL: no docs"; exit 1; }
test -f "$root/usr/include/sewerplan/version.h" || { echo "FAIL: no version.h"; exit 1; }
for f in "$sp" "$root"/usr/lib/libsewerplan_*.a "$root"/usr/lib/sewerplan/*.so; do
  if objdump -h "$f" 2>/dev/null | grep -q '\.debug_info'; then echo "FAIL: $f has debug info"; exit 1; fi
done
if ls "$build"/python/sewerplan/_sewerplan*.so > /dev/null 2>&1; then
  pydir="$root/usr/lib/python3/dist-packages"
  module=$(ls "$pydir"/sewerplan/_sewerplan*.so) || { echo "FAIL: no Python module"; exit 1; }
  if objdump -h "$module" | grep -q '\.debug_info'; then echo "FAIL: $module has debug info"; exit 1; fi
  dpkg-deb --field "$deb" Depends | grep -q 'python3' || { echo "FAIL: no python3 dependency"; exit 1; }
  py=(env PYTHONDONTWRITEBYTECODE=1 PYTHONPATH="$pydir" /usr/bin/python3)
  out=$(cd "$work" && "${py[@]}" -c 'import sewerplan; print(sewerplan.__file__)')
  case "$out" in "$pydir"/*) ;; *) echo "FAIL: imported sewerplan from $out"; exit 1 ;; esac
  example="$root/usr/share/sewerplan/examples/python/plan_ais.py"
  test -x "$example" || { echo "FAIL: no $example"; exit 1; }
  (cd "$work" && "${py[@]}" "$example" "$data") > "$work/python.out"
  grep -q '14 steps, 585.4 s, 19.5 Wh' "$work/python.out" || {
    echo "FAIL: the Python example said:"; cat "$work/python.out"; exit 1; }
  python_ok=", Python module"
fi
# A consumer project against the unpacked package.
cmake -S "$src/tests/consumer" -B "$work/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$root/usr" > /dev/null
cmake --build "$work/consumer" > /dev/null
out=$("$work/consumer/consumer" "$data/map.json")
[ "$out" = "ais-testbed: 12 manholes, 14 pipes" ] || { echo "FAIL: consumer said '$out'"; exit 1; }
echo "deb: installed into a scratch root, --version, plan, PNG module${gis_ok:-}, man page, completion, consumer${python_ok:-}: ok"
