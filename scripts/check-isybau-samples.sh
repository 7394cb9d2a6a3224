#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The acceptance check of issue 15 on the official ISYBAU-XML samples, which we may not ship.
#
#   bash scripts/check-isybau-samples.sh DIR
#
# DIR holds the samples of the "Arbeitshilfen Abwasser" (arbeitshilfen-abwasser.de / bfr-abwasser.de,
# Materialien, Beispieldatensaetze), under their published names:
#   ISYBAU_XML-2013-Stammdaten.xml                            (ISYBAU_XML_2013_Schema_Beispieldaten.zip)
#   ISYBAU_XML-2017-Stammdaten.xml                            (the XML-2017 sample data)
#   ISYBAU_XML-2013-Zustandsdaten_DIN_EN_13508-2_AH_Abwasser.xml   (optional: the findings check)
# The sewerplan binary is $SEWERPLAN, else build/bin/sewerplan, else `sewerplan` on the PATH.
# ISYBAU_TOLERANCE_DEG (default 3) is how far a slot's direction may differ between the two.
#
# It checks, and exits 1 naming every difference, that
#  1. both Stammdaten files import (validate --json: valid);
#  2. every manhole of both files has the same pipes in its slots, and each slot the same direction
#     within the tolerance (the 2013 sample's pipe lines end at the manholes' floor points, 5 to
#     20 cm off the cover: the defect of issue 15 gave all slots of a manhole one direction);
#  3. both give the same driveable network for makro-plus (info --profile --json: pipes too narrow
#     or too wide, passages beyond the limits, what is reachable from the exits);
#  4. the Zustandsdaten joined to the 2013 Stammdaten (convert --condition) put every finding on
#     its pipe at its position: the findings are counted again here, from the XML, independently
#     of sewerplan's reader (every optical inspection of each Haltung, Anlagentyp 1, covers a
#     stretch from where it began to its farthest station or Inspektionslaenge, the whole pipe if
#     it reached the far node, BCE, without BDC; a finding stands unless a later inspection, by
#     Inspektionsdatum and Uhrzeit, covered its place; station from where the inspection began,
#     so offset = station with the flow (O), length - station against it (U)), and the two lists
#     must be equal to 1 cm;
#  5. every manhole's shaft size is the one its Schacht gives in metres (Unterteil
#     LaengeUnterteil, BreiteUnterteil; else Aufbau LaengeAufbau, BreiteAufbau; issue 31), read
#     again here from the XML.
set -euo pipefail

dir=${1:?usage: check-isybau-samples.sh DIR (the folder with the official ISYBAU samples)}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bin=${SEWERPLAN:-}
if [[ -z $bin ]]; then
  if [[ -x $here/build/bin/sewerplan ]]; then bin=$here/build/bin/sewerplan; else bin=sewerplan; fi
fi
tolerance=${ISYBAU_TOLERANCE_DEG:-3}
s13=$dir/ISYBAU_XML-2013-Stammdaten.xml
s17=$dir/ISYBAU_XML-2017-Stammdaten.xml
z13=$dir/ISYBAU_XML-2013-Zustandsdaten_DIN_EN_13508-2_AH_Abwasser.xml
for f in "$s13" "$s17"; do
  [[ -f $f ]] || { echo "check-isybau-samples: FAIL: $f is missing" >&2; exit 1; }
done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

fail=0
for v in 13 17; do
  f=$dir/ISYBAU_XML-20$v-Stammdaten.xml
  if ! "$bin" validate --map "$f" --json >"$out/validate$v.json"; then
    echo "check-isybau-samples: FAIL: $f does not import:" >&2
    cat "$out/validate$v.json" >&2
    fail=1
    continue
  fi
  "$bin" convert --map "$f" -o "$out/map$v.json" 2>"$out/convert$v.log"
  "$bin" info --map "$f" --profile makro-plus --json >"$out/info$v.json" 2>/dev/null
done
[[ $fail == 0 ]] || exit 1

joined=""
if [[ -f $z13 ]]; then
  "$bin" convert --map "$s13" --condition "$z13" -o "$out/joined.json" 2>"$out/join.log"
  joined=$out/joined.json
else
  echo "check-isybau-samples: note: $z13 not found: findings not checked" >&2
fi

python3 - "$out" "$tolerance" "$z13" "$joined" "$s13" "$s17" <<'PY'
import json, sys, xml.etree.ElementTree as ET
out, tolerance, z13, joined = sys.argv[1], float(sys.argv[2]), sys.argv[3], sys.argv[4]
problems = []

def load(name):
    with open(f"{out}/{name}", encoding="utf-8") as f:
        return json.load(f)

m13, m17 = load("map13.json"), load("map17.json")

# 2. Slots: the same pipes, the same directions.
def slots(m):
    return {h["name"]: {s["pipe"]: s["azimuth_deg"] for s in h.get("slots", [])} for h in m["manholes"]}
a, b = slots(m13), slots(m17)
for name in sorted(set(a) ^ set(b)):
    problems.append(f"manhole {name} is only in the {'2013' if name in a else '2017'} sample")
compared, worst, multi = 0, (0.0, ""), 0
for name in sorted(set(a) & set(b)):
    if set(a[name]) != set(b[name]):
        problems.append(f"manhole {name}: pipes {sorted(a[name])} (2013) vs {sorted(b[name])} (2017)")
        continue
    multi += len(a[name]) >= 2
    for pipe in a[name]:
        d = abs((a[name][pipe] - b[name][pipe] + 180) % 360 - 180)
        compared += 1
        if d > worst[0]:
            worst = (d, f"{name}/{pipe}")
        if d > tolerance:
            problems.append(f"manhole {name}, pipe {pipe}: azimuth {a[name][pipe]:.2f} (2013) vs "
                            f"{b[name][pipe]:.2f} (2017) deg, {d:.2f} > {tolerance:g}")
# A manhole whose slots all point one way is the defect of issue 15.
for name, s in sorted(a.items()):
    if len(s) >= 2 and max(s.values()) - min(s.values()) < 1e-6:
        problems.append(f"manhole {name}: all {len(s)} slots of the 2013 sample point at {min(s.values()):.2f} deg")
print(f"slots: {compared} in {len(set(a) & set(b))} manholes ({multi} with two or more pipes) "
      f"compared; largest difference {worst[0]:.2f} deg ({worst[1] or '-'})")

# 3. The driveable network.
i13, i17 = load("info13.json")["driveability"], load("info17.json")["driveability"]
def passages(i):
    return sorted((p["manhole"], tuple(sorted((p["from_pipe"], p["to_pipe"])))) for p in i["passages"]
                  if p.get("turn_exceeded") or p.get("step_exceeded"))
for key in ("too_narrow", "too_wide"):
    if sorted(i13[key]) != sorted(i17[key]):
        problems.append(f"{key}: {sorted(set(i13[key]) ^ set(i17[key]))} differ")
if passages(i13) != passages(i17):
    problems.append(f"passages beyond the limits differ: {sorted(set(passages(i13)) ^ set(passages(i17)))}")
if i13["reachable"] != i17["reachable"]:
    problems.append(f"reachable: {i13['reachable']} (2013) vs {i17['reachable']} (2017)")
def reach(i):
    r = i["reachable"]
    return f"{len(r['manholes'])} manholes, {len(r['pipes'])} pipes, {r['length_m']:.1f} m"
print(f"driveable (makro-plus): reachable {reach(i13)} (2013), {reach(i17)} (2017); "
      f"{len(i13['too_narrow'])} pipes too narrow; {len(passages(i13))} passages beyond the limits")

# 5. Shaft sizes, read again from the XML: the smaller of the Unterteil's (else the Aufbau's)
# length and width, in metres.
def lnx(e): return e.tag.rsplit("}", 1)[-1]
def sub(e, name):
    return next((c for c in e if lnx(c) == name), None) if e is not None else None
def num(e, name):
    c = sub(e, name)
    try:
        return float((c.text or "").strip()) if c is not None else None
    except ValueError:
        return None
for v, m in (("13", m13), ("17", m17)):
    expected_sizes = {}
    for obj in ET.parse(sys.argv[5 if v == "13" else 6]).getroot().iter():
        if lnx(obj) != "AbwassertechnischeAnlage" or sub(obj, "Knoten") is None:
            continue
        schacht = sub(sub(obj, "Knoten"), "Schacht")
        for part, l, w in (("Unterteil", "LaengeUnterteil", "BreiteUnterteil"),
                           ("Aufbau", "LaengeAufbau", "BreiteAufbau")):
            sizes = [x for x in (num(sub(schacht, part), l), num(sub(schacht, part), w)) if x and x > 0]
            if sizes:
                expected_sizes[(sub(obj, "Objektbezeichnung").text or "").strip()] = min(sizes)
                break
    got_sizes = {h["name"]: h["diameter_m"] for h in m["manholes"]}
    wrong = [n for n, d in expected_sizes.items() if n in got_sizes and abs(got_sizes[n] - d) > 1e-9]
    for n in wrong[:10]:
        problems.append(f"20{v}: manhole {n}: diameter {got_sizes[n]} m, its Schacht gives {expected_sizes[n]} m")
    sizes = sorted({d for n, d in got_sizes.items() if n in expected_sizes})
    print(f"shafts (20{v}): {len(expected_sizes)} manholes give a size, "
          f"{len(expected_sizes) - len(wrong)} read so; sizes {', '.join(f'{d:g}' for d in sizes)} m")

# 4. Findings, counted again from the XML.
if joined:
    mj = json.load(open(joined, encoding="utf-8"))
    lengths = {p["name"]: p["length_m"] for p in mj["pipes"]}
    def ln(e): return e.tag.rsplit("}", 1)[-1]
    def child(e, name):
        return next((c for c in e if ln(c) == name), None)
    def text(e, name):
        c = child(e, name) if e is not None else None
        return (c.text or "").strip() if c is not None else ""
    inspections = {}  # Haltung -> its inspections, across every entry of that name, in file order
    for obj in ET.parse(z13).getroot().iter():
        if ln(obj) != "InspizierteAbwassertechnischeAnlage":
            continue
        if text(obj, "Anlagentyp") not in ("", "1"):
            continue
        pipe = text(obj, "Objektbezeichnung")
        for i in (c for c in obj if ln(c) == "OptischeInspektion"):
            rohr = child(i, "Rohrleitung")
            against = text(rohr, "Inspektionsrichtung") == "U"
            found = [(text(r, "InspektionsKode"), float(text(r, "Station"))) for r in i.iter()
                     if ln(r) == "RZustand"]
            reached = max([s for _, s in found] + [float(text(rohr, "Inspektionslaenge") or 0)])
            codes = {c for c, _ in found}
            if pipe in lengths and "BCE" in codes and "BDC" not in codes:
                reached = max(reached, lengths[pipe])
            inspections.setdefault(pipe, []).append(
                (text(i, "Inspektionsdatum") + "T" + text(i, "Uhrzeit"), against, reached, found))
    expected = []
    for pipe, history in inspections.items():
        if pipe not in lengths:
            continue
        L = lengths[pipe]
        def at(against, station): return L - station if against else station
        for k, (when, against, _, found) in enumerate(history):
            for code, station in found:
                offset = at(against, station)
                def covers(j):
                    w, a, reached, _ = history[j]
                    if j == k or w < when or (w == when and (a != against or j < k)):
                        return False
                    lo, hi = sorted((at(a, 0), at(a, reached)))
                    return lo - 0.01 <= offset <= hi + 0.01
                if not any(covers(j) for j in range(len(history))):
                    expected.append((pipe, code, min(max(offset, 0.0), L)))
    got = [(f["pipe"], f["code"], f["offset_m"]) for f in mj.get("findings", [])]
    def key(t): return (t[0], t[1], round(t[2], 2))
    e, g = sorted(map(key, expected)), sorted(map(key, got))
    missing = [x for x in e if x not in g]
    extra = [x for x in g if x not in e]
    for x in missing[:20]:
        problems.append(f"finding {x[1]} on pipe {x[0]} at {x[2]:.2f} m is not in the joined map")
    for x in extra[:20]:
        problems.append(f"the joined map has finding {x[1]} on pipe {x[0]} at {x[2]:.2f} m, the file not")
    if len(missing) + len(extra) > 40:
        problems.append(f"... {len(missing)} missing and {len(extra)} extra findings in all")
    print(f"findings: {len(e)} counted in the Zustandsdaten on {len({x[0] for x in e})} Haltungen of the map, "
          f"{len(g)} in the joined map")

for p in problems:
    print(f"check-isybau-samples: FAIL: {p}", file=sys.stderr)
if problems:
    print(f"check-isybau-samples: FAILED ({len(problems)} problems)", file=sys.stderr)
    sys.exit(1)
print("check-isybau-samples: OK")
PY
