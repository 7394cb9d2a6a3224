#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Sweeps real sewer files through sewerplan and reports what it made of each.

For every map file under the given directories (SWMM .inp, ISYBAU .xml, JSON maps, the ASCII
database .sewer, GeoPackages, Shapefiles, GeoJSON), it runs
  1. `sewerplan info --map FILE --json`: imported, refused (by error code and reason), crashed
     (killed by a signal, or an exit code sewerplan never uses) or hung (over the time limit);
  2. for an imported file, the GIS round trips a user makes through QGIS:
     `convert` to a JSON map (A), `export-geojson` (a map without a CRS is placed with
     `--crs EPSG:25832`); that GeoJSON read back as `--map`, and GDAL's `ogr2ogr` to a GeoPackage
     of one layer per kind of feature in the map's CRS, read back: each JSON map (B) is compared
     with A field by field: every manhole, slot, pipe, inspection point and finding,
     each number within the precision GeoJSON's WGS84 coordinates keep (1 cm for positions, 0.01 degrees
     for azimuths, 1 mm for everything else).
It prints a Markdown report (the one for the shipped files is docs/formats/sweep.md) and exits 1 if
any file crashed, hung or changed in the round trip.

Not part of the test command: it runs every file through several processes. Usage:
  python3 scripts/sweep-real-files.py --sewerplan build/release/apps/sewerplan/sewerplan \
      [--ogr2ogr ogr2ogr] [--timeout 60] [DIR_OR_FILE ...]   (default: datasets ../shared/datasets)
"""

import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
from collections import Counter
from pathlib import Path

MAP_SUFFIXES = {".inp", ".xml", ".json", ".sewer", ".gpkg", ".shp", ".geojson"}
# Exit codes sewerplan documents (README): anything else is a crash.
KNOWN_EXITS = {0, 1, 2, 3, 4, 5, 6}


def is_map_candidate(path: Path) -> bool:
    if path.suffix.lower() not in MAP_SUFFIXES:
        return False
    if path.suffix.lower() == ".json":
        # Missions, risk tables, fault scenarios and field mappings are JSON too: only maps.
        try:
            with open(path, "rb") as f:
                head = f.read(4096)
        except OSError:
            return False
        return b'"sewerplan-map"' in head or b'"FeatureCollection"' in head
    if path.suffix.lower() == ".xml":
        try:
            with open(path, "rb") as f:
                head = f.read(8192)
        except OSError:
            return False
        # Condition data (Zustandsdaten) alone is not a network.
        return b"AbwassertechnischeAnlage" in head or b"Identifikation" in head
    return True


def find_files(roots):
    for root in roots:
        p = Path(root)
        if p.is_file():
            yield p
            continue
        for f in sorted(p.rglob("*")):
            if f.is_file() and is_map_candidate(f):
                yield f


def run(cmd, timeout):
    """(status, exit code, stdout, stderr): status is ok, exit, crash or hang."""
    try:
        proc = subprocess.run(cmd, capture_output=True, timeout=timeout, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        return "hang", None, "", ""
    out = proc.stdout.decode("utf-8", "replace")
    err = proc.stderr.decode("utf-8", "replace")
    if proc.returncode < 0:
        return "crash", proc.returncode, out, err + f" (signal {signal.Signals(-proc.returncode).name})"
    if proc.returncode not in KNOWN_EXITS:
        return "crash", proc.returncode, out, err
    return ("ok" if proc.returncode == 0 else "exit"), proc.returncode, out, err


def error_of(stdout):
    try:
        doc = json.loads(stdout)
        e = doc.get("error", {})
        return e.get("code", "?"), e.get("message", "?")
    except (ValueError, AttributeError):
        return "?", stdout.strip()[:200]


def keyed(items, key="name"):
    return {str(i.get(key)): i for i in items or []}


def tolerance(field):
    if field in ("x_m", "y_m"):
        return 0.01
    if field.endswith("_deg"):
        return 0.01
    return 0.001


def compare_objects(kind, name, a, b, changes):
    for field in sorted(set(a) | set(b)):
        va, vb = a.get(field), b.get(field)
        if field == "slots":
            sa, sb = va or [], vb or []
            if len(sa) != len(sb):
                changes.append(f"{kind} {name}: {len(sa)} slots -> {len(sb)}")
                continue
            for i, (x, y) in enumerate(zip(sa, sb)):
                compare_objects(kind, f"{name} slot {i + 1}", x, y, changes)
            continue
        if isinstance(va, (int, float)) and isinstance(vb, (int, float)) \
                and not isinstance(va, bool) and not isinstance(vb, bool):
            if abs(va - vb) > tolerance(field):
                changes.append(f"{kind} {name}: {field} {va} -> {vb}")
        elif va != vb:
            changes.append(f"{kind} {name}: {field} {json.dumps(va)} -> {json.dumps(vb)}")


def compare_maps(a, b):
    changes = []
    for kind, key in (("manholes", "name"), ("pipes", "name"), ("inspection_points", "name")):
        ka, kb = keyed(a.get(kind), key), keyed(b.get(kind), key)
        for name in sorted(set(ka) - set(kb)):
            changes.append(f"{kind}: {name} lost")
        for name in sorted(set(kb) - set(ka)):
            changes.append(f"{kind}: {name} added")
        for name in sorted(set(ka) & set(kb)):
            compare_objects(kind[:-1] if kind != "inspection_points" else "inspection point",
                            name, ka[name], kb[name], changes)
    fa, fb = a.get("findings") or [], b.get("findings") or []
    if len(fa) != len(fb):
        changes.append(f"findings: {len(fa)} -> {len(fb)}")
    if a.get("crs") != b.get("crs") and a.get("crs") is not None:
        changes.append(f"crs {a.get('crs')} -> {b.get('crs')}")
    return changes


def round_trip(sewerplan, ogr2ogr, path, timeout, work):
    """None if the round trip kept every field, else a list of what it changed or why it failed."""
    a_json, geojson = work / "a.json", work / "net.geojson"
    gpkg, b_json = work / "net.gpkg", work / "b.json"
    for f in (a_json, geojson, gpkg, b_json):
        f.unlink(missing_ok=True)
    status, code, out, err = run([sewerplan, "convert", "--map", str(path), "-o", str(a_json)],
                                 timeout)
    if status != "ok":
        return [f"convert failed ({status} {code}): {err.strip()[:200]}"]
    a = json.loads(a_json.read_text(encoding="utf-8"))
    crs_name = a.get("crs") or "EPSG:25832"
    crs = [] if a.get("crs") else ["--crs", crs_name]
    status, code, out, err = run([sewerplan, "export-geojson", "--map", str(a_json), *crs,
                                  "-o", str(geojson)], timeout)
    if status != "ok":
        return [f"export-geojson failed ({status} {code}): {err.strip()[:200]}"]
    changes = []
    # The GeoJSON itself as --map, then the GeoPackage a QGIS user saves: each kind of feature
    # its own layer, back in the map's CRS.
    status, code, out, err = run([sewerplan, "convert", "--map", str(geojson), "-o", str(b_json)],
                                 timeout)
    if status != "ok":
        changes.append(f"convert of the GeoJSON failed ({status} {code}): {err.strip()[:200]}")
    else:
        b = json.loads(b_json.read_text(encoding="utf-8"))
        if not a.get("crs"):
            b.pop("crs", None)
        changes += ["GeoJSON: " + c for c in compare_maps(a, b)]
    update = []
    for layer in ("manhole", "pipe", "inspection_point", "finding"):
        status, code, out, err = run([ogr2ogr, "-f", "GPKG", *update, str(gpkg), str(geojson),
                                      "-t_srs", crs_name, "-where", f"layer = '{layer}'",
                                      "-nln", layer + "s"], timeout)
        if status != "ok":
            return changes + [f"ogr2ogr failed: {err.strip()[:200]}"]
        update = ["-update"]
    status, code, out, err = run([sewerplan, "convert", "--map", str(gpkg), "-o", str(b_json)],
                                 timeout)
    if status != "ok":
        return changes + [f"convert of the GeoPackage failed ({status} {code}): "
                          f"{err.strip()[:200]}"]
    b = json.loads(b_json.read_text(encoding="utf-8"))
    if not a.get("crs"):
        b.pop("crs", None)
    changes += ["GeoPackage: " + c for c in compare_maps(a, b)]
    return changes or None


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sewerplan", required=True, help="the sewerplan command")
    ap.add_argument("--ogr2ogr", default=shutil.which("ogr2ogr"), help="GDAL's ogr2ogr")
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds a command may take")
    ap.add_argument("--no-round-trip", action="store_true", help="only info --json")
    ap.add_argument("paths", nargs="*", default=["datasets", "../shared/datasets"])
    args = ap.parse_args()

    rows, verdicts = [], Counter()
    refusals = Counter()
    bad = False
    with tempfile.TemporaryDirectory(prefix="sewerplan-sweep-") as tmp:
        work = Path(tmp)
        for path in find_files(args.paths):
            status, code, out, err = run([args.sewerplan, "info", "--map", str(path), "--json"],
                                         args.timeout)
            detail, trip = "", ""
            if status == "ok":
                verdict = "imported"
                try:
                    info = json.loads(out)
                    detail = f"{info.get('manholes', '?')} manholes, {info.get('pipes', '?')} pipes"
                    warnings = [line for line in err.splitlines() if "warning:" in line]
                    if warnings:
                        detail += f", {len(warnings)} warnings (first: {warnings[0][:120]})"
                except ValueError:
                    detail = "info --json printed no JSON"
                    bad = True
                if not args.no_round_trip and args.ogr2ogr:
                    changes = round_trip(args.sewerplan, args.ogr2ogr, path, args.timeout, work)
                    if changes is None:
                        trip = "unchanged"
                    else:
                        trip = f"{len(changes)} changes: " + "; ".join(changes[:5])
                        bad = True
            elif status == "exit":
                err_code, message = error_of(out)
                verdict = f"refused ({err_code})"
                refusals[err_code] += 1
                detail = message.splitlines()[0][:160] if message else ""
            else:
                verdict = status
                detail = (err.strip().splitlines() or [""])[-1][:160]
                bad = True
            verdicts[verdict.split(" ")[0]] += 1
            rows.append((str(path), verdict, detail, trip))

    print("# Sweep of real sewer files\n")
    print("Made by `scripts/sweep-real-files.py` (" + " ".join(sys.argv[1:]) + ").\n")
    print("| verdict | files |\n|---|---|")
    for v, n in sorted(verdicts.items()):
        print(f"| {v} | {n} |")
    if refusals:
        print("\nRefused, by reason: " + ", ".join(f"{k} {n}" for k, n in sorted(refusals.items())))
    print("\n| file | verdict | what | GIS round trip |\n|---|---|---|---|")
    for path, verdict, detail, trip in rows:
        cell = lambda s: s.replace("|", "\\|")
        print(f"| `{path}` | {verdict} | {cell(detail)} | {cell(trip)} |")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
