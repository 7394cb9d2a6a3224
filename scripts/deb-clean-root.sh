#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Acceptance of issues 18 and 33: the Debian packages install and run on a clean Debian 12
# (bookworm) root, and the runtime package alone pulls no -dev package and no compiler.
#
# mmdebstrap makes a minimal bookworm root (essential packages and apt, nothing of sewerplan's
# build); the packages are copied in and installed with `apt-get install ./PACKAGE.deb` in a chroot,
# so that apt resolves their Depends from Debian's mirror: a missing or wrong dependency fails here,
# where the unpacking test (tests/install/deb_test.sh) cannot see it. First the runtime package,
# sewerplan, alone: what apt would install for it (apt-get --simulate) must hold no -dev package and
# no compiler, and is counted. Then, in the chroot, as a user would: `sewerplan --version`, the AIS
# mission planned from the installed example data and compared with the shipped
# paper-corrected.plan, the man page (`man -w` where man-db is, else the file), the bash completion,
# and with GIS: `sewerplan export-geojson` and a GeoPackage written from it by the host's ogr2ogr
# (gdal-bin) read back by the installed `sewerplan convert`; `sewerplan-compare`; and `sewerplan
# serve` answering with the installed page and its map list. Then python3-sewerplan: the installed
# Python example (plan_ais.py) and the GeoPackage read by the Python module. With --consumer,
# sewerplan-dev and a compiler, and a project built against the CMake package.
#
# Not part of the test command: it downloads a few hundred MB the first time (the bookworm base,
# then the package's dependencies). Caches, under CACHE (default BUILD/deb-clean-root): the base
# root as a tarball, apt's package lists and its downloaded .debs. Every run unpacks the base into a
# new root, so the root is clean each time and reruns download nothing new. --keep leaves the last
# root in CACHE/root to look into (chroot CACHE/root); --fresh drops the caches first.
#
# Usage (as root, on Debian 12; paths relative to the current directory):
#   scripts/deb-clean-root.sh [--deb FILE] [--cache DIR] [--keep] [--fresh] [--consumer] [--mirror URL] [BUILD]
# --deb FILE: the runtime package sewerplan_*.deb; python3-sewerplan and sewerplan-dev are taken
# from the same folder (scripts/build-deb.sh writes all three to build/deb/packages).
# --consumer: also install sewerplan-dev, cmake, g++ and ninja in the root and build tests/consumer
# against the installed CMake package (find_package(sewerplan): the -dev Depends).
# BUILD (default: build) is a configured and built tree; without --deb the packages are made in it
# with cpack. The mirror defaults to Debian's (http://deb.debian.org/debian).
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
build=build deb="" cache="" keep=0 fresh=0 consumer=0 mirror=http://deb.debian.org/debian
while [ $# -gt 0 ]; do
  case "$1" in
    --deb) deb=$(realpath "$2"); shift 2 ;;
    --cache) cache=$2; shift 2 ;;
    --keep) keep=1; shift ;;
    --consumer) consumer=1; shift ;;
    --fresh) fresh=1; shift ;;
    --mirror) mirror=$2; shift 2 ;;
    -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) echo "deb-clean-root: unknown option $1 (--help)" >&2; exit 2 ;;
    *) build=$1; shift ;;
  esac
done
[ "$(id -u)" -eq 0 ] || { echo "deb-clean-root: run as root (chroot and mounts)" >&2; exit 2; }
start=$(date +%s)
step() { echo "[$(($(date +%s) - start)) s] $*"; }

# The package.
if [ -z "$deb" ]; then
  [ -f "$build/CPackConfig.cmake" ] || { echo "deb-clean-root: $build is not a configured tree" >&2; exit 2; }
  build=$(cd "$build" && pwd)
  out="$build/deb-clean-root-package"
  rm -rf "$out"
  step "cpack -G DEB in $build"
  (cd "$build" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$out" > "$build/deb-clean-root-cpack.log" 2>&1) || {
    cat "$build/deb-clean-root-cpack.log"; exit 1; }
  deb=$(ls "$out"/sewerplan_*_amd64.deb)
fi
[ -f "$deb" ] || { echo "deb-clean-root: no package $deb" >&2; exit 2; }
# The version without its Debian revision, as `sewerplan --version` prints it.
version=$(dpkg-deb --field "$deb" Version)
version=${version%-*}
py_deb=$(ls "$(dirname "$deb")"/python3-sewerplan_*_amd64.deb 2> /dev/null || true)
dev_deb=$(ls "$(dirname "$deb")"/sewerplan-dev_*_amd64.deb 2> /dev/null || true)
for d in "$deb" $py_deb $dev_deb; do
  step "package $(basename "$d") ($(du -k "$d" | cut -f1) KiB), Depends: $(dpkg-deb --field "$d" Depends)"
done

cache=${cache:-$build/deb-clean-root}
mkdir -p "$cache"
cache=$(cd "$cache" && pwd -P)
[ "$fresh" -eq 0 ] || rm -rf "$cache/bookworm-base.tar" "$cache/apt-lists" "$cache/apt-archives"
if ! command -v mmdebstrap > /dev/null; then
  step "installing mmdebstrap"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq mmdebstrap > /dev/null
fi
if [ ! -f "$cache/bookworm-base.tar" ]; then
  step "mmdebstrap: a minimal bookworm root from $mirror"
  security=${mirror%/debian}/debian-security
  mmdebstrap --quiet --variant=apt --format=tar bookworm "$cache/bookworm-base.tar.partial" \
    "deb $mirror bookworm main" "deb $mirror bookworm-updates main" \
    "deb $security bookworm-security main"
  mv "$cache/bookworm-base.tar.partial" "$cache/bookworm-base.tar"
fi

# A new root from the base, with the caches and the kernel's file systems mounted.
root="$cache/root"
mounts=()
# Removes the root only when nothing is mounted in it any more (a bound /dev must never be emptied).
remove_root() {
  for m in dev/pts dev proc sys var/cache/apt/archives var/lib/apt/lists; do
    umount "$root/$m" 2> /dev/null || true
  done
  if grep -q " $root/" /proc/mounts; then
    echo "deb-clean-root: still mounted under $root, not removing it:" >&2
    grep " $root/" /proc/mounts >&2
    return 1
  fi
  rm -rf --one-file-system "$root"
}
cleanup() {
  for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do umount "${mounts[i]}" 2> /dev/null || true; done
  if [ "$keep" -eq 0 ]; then remove_root; fi
}
trap cleanup EXIT
if [ -d "$root" ]; then remove_root; fi
mkdir -p "$root" "$cache/apt-lists/partial" "$cache/apt-archives/partial"
step "unpacking the base root into $root"
tar -C "$root" -xpf "$cache/bookworm-base.tar"
bind() {
  mkdir -p "$root/$2"
  mount --bind "$1" "$root/$2"
  mounts+=("$root/$2")
}
bind /dev dev
bind /dev/pts dev/pts
mount -t proc proc "$root/proc" && mounts+=("$root/proc")
mount -t sysfs sysfs "$root/sys" && mounts+=("$root/sys")
bind "$cache/apt-lists" var/lib/apt/lists
bind "$cache/apt-archives" var/cache/apt/archives
cp -L /etc/resolv.conf "$root/etc/resolv.conf"
in_root() {
  env -i PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 \
    DEBIAN_FRONTEND=noninteractive chroot "$root" "$@"
}
in_root dpkg-query -W sewerplan > /dev/null 2>&1 && { echo "FAIL: the base root has sewerplan"; exit 1; }

fail() { echo "FAIL: $*"; exit 1; }
# apt_install NAME FILE...: installs the packages (a .deb by its path in the root), without
# recommends: a package must run with what its Depends bring. Prints what apt installed.
apt_install() {
  local name=$1
  shift
  if ! in_root apt-get install -y -q --no-install-recommends "$@" > "$cache/apt-install-$name.log" 2>&1; then
    tail -30 "$cache/apt-install-$name.log"
    fail "apt-get install $* in a clean bookworm root"
  fi
  grep -E '^(Need to get|After this operation)' "$cache/apt-install-$name.log" || true
}
for d in "$deb" $py_deb $dev_deb; do cp "$d" "$root/tmp/"; done
rt=/tmp/$(basename "$deb")
in_root apt-get update -qq

# The runtime package alone: what apt would install (the package itself and its dependencies, on
# top of the base root) holds no -dev package and no compiler.
step "apt-get install --simulate $rt: what the runtime package pulls"
in_root apt-get install --simulate --no-install-recommends "$rt" > "$cache/apt-simulate.log" 2>&1 || {
  tail -20 "$cache/apt-simulate.log"; fail "apt-get install --simulate $rt"; }
awk '$1 == "Inst" {print $2}' "$cache/apt-simulate.log" | sort > "$cache/runtime-pulls.txt"
build_tools='-dev$|^(gcc|g\+\+|cpp|c\+\+|clang|clang\+\+|binutils)(-[0-9.]+)?$|^(clang|llvm)-|^binutils-'
found=0
grep -E -e "$build_tools" "$cache/runtime-pulls.txt" > "$cache/runtime-build-tools.txt" || found=$?
[ "$found" -ne 2 ] || fail "grep of what apt would install"
[ "$found" -eq 1 ] || fail "the runtime package pulls build tools: $(tr '\n' ' ' < "$cache/runtime-build-tools.txt")"
echo "ok: the runtime package pulls $(wc -l < "$cache/runtime-pulls.txt") packages (itself included), none -dev, no compiler ($cache/runtime-pulls.txt)"
step "apt-get install $rt (apt resolves its Depends)"
apt_install runtime "$rt"
# shellcheck disable=SC2016 # dpkg-query's own ${...} fields
step "installed: $(in_root dpkg-query -W -f='${Package} ${Version} ${Status}' sewerplan)"
got=$(in_root sewerplan --version) || fail "sewerplan --version did not run"
[ "$got" = "sewerplan $version" ] || fail "sewerplan --version said '$got', want 'sewerplan $version'"
echo "ok: sewerplan --version: $got"

data=/usr/share/sewerplan/datasets/ais-testbed
in_root sh -c "cd /tmp && sewerplan plan --map $data/map.json --mission $data/missions/paper.json -q > /tmp/paper.plan" ||
  fail "sewerplan plan of the AIS mission"
cmp "$root/tmp/paper.plan" "$root$data/plans/paper-corrected.plan" || fail "the plan differs from paper-corrected.plan"
echo "ok: the AIS mission's plan is the shipped paper-corrected.plan ($(wc -l < "$root/tmp/paper.plan") lines)"
in_root sewerplan check --map "$data/map.json" --mission "$data/missions/paper.json" "$data/plans/paper-corrected.plan" ||
  fail "sewerplan check of paper-corrected.plan"

if in_root sh -c 'command -v man' > /dev/null; then
  page=$(in_root man -w sewerplan) || fail "man -w sewerplan"
else
  page=/usr/share/man/man1/sewerplan.1.gz  # gzipped, as Debian's policy wants
  [ -f "$root$page" ] || fail "no man page $page: $(ls "$root"/usr/share/man/man1/sewerplan* 2>&1)"
fi
in_root sh -c "zcat -f $page | grep -q '^\.TH SEWERPLAN'" || fail "$page is not a man page"
echo "ok: man page $page"
in_root bash -c 'source /usr/share/bash-completion/completions/sewerplan && complete -p sewerplan' > /dev/null ||
  fail "the bash completion does not load"
echo "ok: bash completion loads"

if in_root sewerplan --help | grep -q export-geojson; then
  in_root sewerplan export-geojson --map "$data/map.json" --assume-crs EPSG:25832 \
    --mission "$data/missions/paper.json" --plan-route --profile makro-plus -o /tmp/ais.geojson > /dev/null ||
    fail "sewerplan export-geojson"
  /usr/bin/python3 -c 'import json, sys; j = json.load(open(sys.argv[1])); assert j["type"] == "FeatureCollection" and j["features"], j.keys()' \
    "$root/tmp/ais.geojson" || fail "export-geojson wrote no FeatureCollection"
  echo "ok: export-geojson: $(/usr/bin/python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))["features"]))' "$root/tmp/ais.geojson") features"
  if command -v ogr2ogr > /dev/null; then
    # The GeoPackage is written on the host (gdal-bin is no dependency of the package).
    gpkg="$root/tmp/ais.gpkg"
    ogr2ogr -f GPKG "$gpkg" "$root/tmp/ais.geojson" -t_srs EPSG:25832 -where "layer = 'manhole'" -nln manholes
    ogr2ogr -f GPKG -update "$gpkg" "$root/tmp/ais.geojson" -t_srs EPSG:25832 -where "layer = 'pipe'" -nln pipes
    in_root sewerplan convert --map /tmp/ais.gpkg -o /tmp/back.json > /dev/null || fail "sewerplan convert of a GeoPackage"
    got=$(in_root sewerplan info --map /tmp/back.json --json | /usr/bin/python3 -c 'import json, sys; j = json.load(sys.stdin); print(j["manholes"], j["pipes"], j["crs"])')
    [ "$got" = "12 14 EPSG:25832" ] || fail "the GeoPackage came back as '$got', want '12 14 EPSG:25832'"
    echo "ok: GeoPackage import (sewerplan convert): 12 manholes, 14 pipes, EPSG:25832"
  else
    echo "skipped: GeoPackage import (no ogr2ogr on the host: apt-get install gdal-bin)"
  fi
fi
if [ -f "$root/usr/bin/sewerplan-compare" ]; then
  in_root sewerplan-compare --help > /dev/null || fail "sewerplan-compare --help"
  echo "ok: sewerplan-compare runs"
fi
if [ -f "$root/usr/share/sewerplan/web/index.html" ]; then
  # The operator station from the installed page: the server starts, serves the page and its API.
  # exec: the background job is the server itself (env, chroot and sewerplan exec each other), so
  # that killing it leaves nothing running in the root.
  # --port 0: any free port (the root shares the host's network); the URL is read from its output.
  (exec env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 chroot "$root" \
    sewerplan serve --map "$data/map.json" --port 0 > "$cache/serve.log" 2>&1) &
  serve_pid=$!
  url=""
  for _ in $(seq 1 100); do
    url=$(grep -oE 'http://127\.0\.0\.1:[0-9]+/' "$cache/serve.log" 2> /dev/null | head -1 || true)
    [ -n "$url" ] && break
    sleep 0.1
  done
  # From the host's python3: the root shares its network, and the runtime package brings no python3.
  got=$(/usr/bin/python3 - "$url" <<'PY' || true
import json, sys, urllib.request
base = sys.argv[1].rstrip("/")
page = urllib.request.urlopen(base + "/", timeout=5).read().decode()
maps = json.load(urllib.request.urlopen(base + "/api/maps", timeout=5))
print("<html" in page.lower(), len(maps["maps"]) if isinstance(maps, dict) else len(maps))
PY
)
  kill "$serve_pid" 2> /dev/null || true
  wait "$serve_pid" 2> /dev/null || true
  [ "$got" = "True 1" ] || { cat "$cache/serve.log"; fail "sewerplan serve answered '$got', want the page and 1 map"; }
  echo "ok: sewerplan serve: the installed page and /api/maps"
fi
if [ -n "$py_deb" ]; then
  py=/tmp/$(basename "$py_deb")
  step "apt-get install $py"
  apt_install python "$py"
  example=/usr/share/sewerplan/examples/python/plan_ais.py
  [ -f "$root$example" ] || fail "no $example"
  in_root sh -c "cd /tmp && python3 $example" > "$cache/python.out" 2>&1 || {
    cat "$cache/python.out"; fail "python3 $example"; }
  grep -q '14 steps, 585.4 s, 19.5 Wh' "$cache/python.out" || {
    cat "$cache/python.out"; fail "the Python example's plan"; }
  echo "ok: python3 $example: $(grep 'steps' "$cache/python.out")"
  if [ -f "$root/tmp/ais.gpkg" ]; then
    got=$(in_root python3 -c 'import sewerplan; m = sewerplan.read_map("/tmp/ais.gpkg"); print(m.manhole_count, m.pipe_count)') ||
      fail "the Python module cannot read a GeoPackage"
    [ "$got" = "12 14" ] || fail "Python read the GeoPackage as '$got'"
    echo "ok: GeoPackage import (Python sewerplan.read_map): 12 manholes, 14 pipes"
  fi
fi
if [ "$consumer" -eq 1 ]; then
  [ -n "$dev_deb" ] || fail "--consumer: no sewerplan-dev package beside $deb"
  step "consumer: apt-get install $(basename "$dev_deb") cmake g++ ninja-build, then a project with find_package(sewerplan)"
  apt_install consumer "/tmp/$(basename "$dev_deb")" cmake g++ ninja-build
  cp -r "$src/tests/consumer" "$root/tmp/consumer-src"
  in_root sh -c 'cmake -S /tmp/consumer-src -B /tmp/consumer -G Ninja > /tmp/consumer.log 2>&1 &&
    cmake --build /tmp/consumer >> /tmp/consumer.log 2>&1' || { cat "$root/tmp/consumer.log"; fail "the consumer project"; }
  got=$(in_root /tmp/consumer/consumer "$data/map.json")
  [ "$got" = "ais-testbed: 12 manholes, 14 pipes" ] || fail "the consumer said '$got'"
  echo "ok: a project built against the installed CMake package: $got"
fi
step "deb-clean-root: $(basename "$deb")${py_deb:+, $(basename "$py_deb")}$([ "$consumer" -eq 1 ] && echo ", $(basename "$dev_deb")") install and run on a clean Debian 12 root: ok"
