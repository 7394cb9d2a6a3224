#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Write SYNTHETIC inspection findings for a sewerplan JSON map as ISYBAU Zustandsdaten.

For networks that have no inspection data (SWMM models): the campaign of issue 15 needs a real
network with condition data, and invented findings that follow the way real ones fall are the
next best thing. Nothing in the output was observed; the file says so in its comment.

    sewerplan convert --map datasets/swmm/swmmio-state-plane.inp -o /tmp/net.json
    python3 scripts/synthetic-zustand.py /tmp/net.json -o zustand.xml --seed 1 --per-km 15

The distribution (documented in datasets/condition/README.md):
- each pipe gets a Poisson number of findings with mean per_km x length_km x w, where the pipe's
  weight w is 2 for small pipes (diameter below 0.35 m), 1 up to 0.5 m, 0.5 above (small pipes
  clog and root more: their joints are closer to the roots and a deposit takes more of the
  section) and x1.5 for flat pipes (fall below 0.5 %: settled deposits);
- the code of each finding is drawn from the base shares BBA roots 30, BBC settled deposits 25,
  BBB attached deposits 15, BAJ displaced joint 15, BAA deformation 8, BBE obstacle 5, BAC
  collapse 2 (percent), with roots x2 in small pipes and settled deposits x2 in flat ones;
- quantification 1 (share of the cross-section lost, percent): roots 5..40, deposits 5..30,
  obstacles 5..25, deformation 3..15, uniform; none for joints and collapses;
- the position is uniform along the pipe, at least 0.5 m from either end;
- each pipe is inspected once, with the flow (O) or against it (U) at random, and its stations
  are written from where that inspection began, between its BCD (start) and BCE (end) markers.
Only random.random() is used, so the same map and seed give the same file on every Python 3.
"""
import argparse
import json
import math
import random
import sys

BASE_SHARES = [("BBA", 30), ("BBC", 25), ("BBB", 15), ("BAJ", 15), ("BAA", 8), ("BBE", 5), ("BAC", 2)]
QUANTITY = {"BBA": (5, 40), "BBC": (5, 30), "BBB": (5, 30), "BBE": (5, 25), "BAA": (3, 15)}
CHARACTERISATION = {"BBA": "B", "BBC": "A", "BBB": "A", "BBE": "C", "BAA": "A", "BAJ": "B", "BAC": "A"}


def poisson(rng, mean):
    # Knuth's method: fine for the small means here.
    limit = math.exp(-mean)
    k, p = 0, rng.random()
    while p > limit:
        k += 1
        p *= rng.random()
    return k


def pick(rng, weighted):
    total = sum(w for _, w in weighted)
    r = rng.random() * total
    for code, w in weighted:
        r -= w
        if r < 0:
            return code
    return weighted[-1][0]


def pipe_inverts(m):
    inverts = {}
    for manhole in m["manholes"]:
        for slot in manhole.get("slots", []):
            inverts.setdefault(slot["pipe"], {})[manhole["name"]] = slot.get("invert_m", manhole.get("z_m", 0))
    return inverts


def findings_for(rng, pipe, inverts, per_km):
    length = pipe["length_m"]
    d = pipe["diameter_m"]
    ends = inverts.get(pipe["name"], {})
    fall = None
    if pipe.get("from") in ends and pipe.get("to") in ends and length > 0:
        fall = abs(ends[pipe["from"]] - ends[pipe["to"]]) / length
    small = d < 0.35
    flat = fall is not None and fall < 0.005
    weight = (2.0 if small else 1.0 if d <= 0.5 else 0.5) * (1.5 if flat else 1.0)
    shares = [(c, w * (2 if (c == "BBA" and small) or (c == "BBC" and flat) else 1)) for c, w in BASE_SHARES]
    out = []
    if length <= 1.0:
        return out
    for _ in range(poisson(rng, per_km * length / 1000.0 * weight)):
        code = pick(rng, shares)
        offset = 0.5 + rng.random() * (length - 1.0)
        q = None
        if code in QUANTITY:
            lo, hi = QUANTITY[code]
            q = round(lo + rng.random() * (hi - lo))
        out.append((offset, code, q))
    out.sort()
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("map", help="a sewerplan JSON map (sewerplan convert --map IN -o OUT.json)")
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--per-km", type=float, default=15.0, help="findings per km of pipe at weight 1")
    args = ap.parse_args()
    with open(args.map, encoding="utf-8") as f:
        m = json.load(f)
    if m.get("format") != "sewerplan-map":
        sys.exit(f"{args.map}: not a sewerplan JSON map (convert it first)")
    rng = random.Random(args.seed)
    inverts = pipe_inverts(m)
    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f"<!-- SYNTHETIC Zustandsdaten for map {m.get('name', '')}: written by scripts/synthetic-zustand.py",
        f"     --seed {args.seed} --per-km {args.per_km:g}; no finding here was observed. -->",
        '<Identifikation xmlns="http://www.ofd-hannover.la/Identifikation">',
        "  <Version>2013-02</Version>",
        "  <Datenkollektive>",
        "    <Zustandsdatenkollektiv>",
    ]
    total = 0
    for pipe in m["pipes"]:
        found = findings_for(rng, pipe, inverts, args.per_km)
        against = rng.random() < 0.5
        if not found:
            continue
        length = pipe["length_m"]
        lines += [
            "      <InspizierteAbwassertechnischeAnlage>",
            f"        <Objektbezeichnung>{pipe['name']}</Objektbezeichnung>",
            "        <Anlagentyp>1</Anlagentyp>",
            "        <OptischeInspektion>",
            "          <Inspektionsdatum>2024-05-01</Inspektionsdatum>",
            "          <Rohrleitung>",
            f"            <Inspektionsrichtung>{'U' if against else 'O'}</Inspektionsrichtung>",
            "            <Inspektionsdaten>",
        ]
        records = [(0.0, "BCD", None)] + [
            (length - off if against else off, code, q) for off, code, q in found
        ] + [(math.floor(length * 100) / 100, "BCE", None)]  # 2 decimals, not past the end
        records.sort(key=lambda r: r[0])
        for station, code, q in records:
            lines.append("              <RZustand>")
            lines.append(f"                <Station>{station:.2f}</Station>")
            lines.append(f"                <InspektionsKode>{code}</InspektionsKode>")
            if code in CHARACTERISATION:
                lines.append(f"                <Charakterisierung1>{CHARACTERISATION[code]}</Charakterisierung1>")
            if q is not None:
                lines.append(f"                <Quantifizierung1Numerisch>{q}</Quantifizierung1Numerisch>")
            lines.append("              </RZustand>")
        total += len(found)
        lines += [
            "            </Inspektionsdaten>",
            "          </Rohrleitung>",
            "        </OptischeInspektion>",
            "      </InspizierteAbwassertechnischeAnlage>",
        ]
    lines += ["    </Zustandsdatenkollektiv>", "  </Datenkollektive>", "</Identifikation>", ""]
    with open(args.output, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))
    print(f"{args.output}: {total} synthetic findings on {len(m['pipes'])} pipes", file=sys.stderr)


if __name__ == "__main__":
    main()
