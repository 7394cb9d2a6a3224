#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Writes the variant fixtures of datasets/isybau/ from street-2017.xml (see README.md):
#   street-optional.xml   optional elements left out, shaft sizes given
#   street-latin1.xml     the network in ISO-8859-1, with umlauts in names
#   street-zustand.xml    ISYBAU Zustandsdaten (inspection findings) for the street network
#   street-polyline.xml   pipe lines as the official 2017 sample writes them: a polyline
#                         (Polygone/Polygon, Polygonart 3) of Kante segments, after an outline ring
# Run from this folder: python3 make_variants.py
import re

base = open("street-2017.xml", encoding="utf-8").read()


def sub(text, old, new):
    assert old in text, old
    return text.replace(old, new, 1)


# --- optional elements ----------------------------------------------------------------------
t = base
t = sub(t, "ISYBAU 2017-07 dialect;", "ISYBAU 2017-07 dialect, optional elements left out;")
# S1: a round shaft of 1.00 m; S2: a rectangular one, 1.20 x 0.80 m (LaengeUnterteil and
# BreiteUnterteil, in metres, as every ISYBAU version writes them).
t = sub(t, "<Schachttiefe>2.5</Schachttiefe>\n",
        "<Schachttiefe>2.5</Schachttiefe>\n            <Unterteil>\n"
        "              <Unterteilform>R</Unterteilform>\n"
        "              <LaengeUnterteil>1.00</LaengeUnterteil>\n            </Unterteil>\n")
t = re.sub(r"(<Objektbezeichnung>S2</Objektbezeichnung>\s*<Objektart>2</Objektart>\s*<Knoten>\s*"
           r"<KnotenTyp>0</KnotenTyp>\s*<Schacht>\s*<Schachttiefe>[\d.]+</Schachttiefe>\n)",
           lambda m: m.group(1) + "            <Unterteil>\n              <Unterteilform>E</Unterteilform>\n"
           "              <LaengeUnterteil>1.20</LaengeUnterteil>\n"
           "              <BreiteUnterteil>0.80</BreiteUnterteil>\n            </Unterteil>\n", t, count=1)
# Pipe S1: circular by its height only, no SohlhoeheZulauf (from S1's floor, 47.50).
t = sub(t, "<SohlhoeheZulauf>47.50</SohlhoeheZulauf>\n          ", "")
t = sub(t, "<Profilbreite>300</Profilbreite>", "<Profilhoehe>300</Profilhoehe>")
# Pipe S2: no Laenge, but a DMPLaenge.
t = sub(t, "<Laenge>30.00</Laenge>\n          <Profil>\n            <Profilart>0</Profilart>\n"
           "            <Profilbreite>500</Profilbreite>",
        "<Haltung>\n            <DMPLaenge>30.00</DMPLaenge>\n          </Haltung>\n"
        "          <Profil>\n            <Profilart>0</Profilart>\n"
        "            <Profilbreite>500</Profilbreite>")
# Pipe S4: no Laenge at all (its line: 12 m).
t = sub(t, "<Laenge>12.00</Laenge>\n          ", "")
open("street-optional.xml", "w", encoding="utf-8").write(t)

# --- Pipe lines as polylines (the official ISYBAU-XML 2017 sample) --------------------------------
t = base
t = sub(t, "ISYBAU 2017-07 dialect;", "ISYBAU 2017-07 dialect, pipe lines as Polygone/Polygon (Polygonart 3);")
t = t.replace("<Kanten>\n", "<Polygone>\n              <Polygon>\n                <Polygonart>3</Polygonart>\n")
t = t.replace("</Kanten>\n", "</Polygon>\n            </Polygone>\n")
# Pipe S3 also has its outline (a closed ring, Polygonart 2) first: not its line.
ring = "".join(
    f"                <Kante>\n                  <Start>\n                    <Rechtswert>{a[0]}</Rechtswert>\n"
    f"                    <Hochwert>{a[1]}</Hochwert>\n                  </Start>\n"
    f"                  <Ende>\n                    <Rechtswert>{b[0]}</Rechtswert>\n"
    f"                    <Hochwert>{b[1]}</Hochwert>\n                  </Ende>\n                </Kante>\n"
    for a, b in [((29.0, 41.0), (31.0, 41.0)), ((31.0, 41.0), (31.0, -1.0)),
                 ((31.0, -1.0), (29.0, -1.0)), ((29.0, -1.0), (29.0, 41.0))])
t = re.sub(r"(<Objektbezeichnung>S3</Objektbezeichnung>\s*<Objektart>1</Objektart>.*?<Polygone>\n)",
           lambda m: m.group(1) + "              <Polygon>\n                <Polygonart>2</Polygonart>\n"
           + ring + "              </Polygon>\n", t, count=1, flags=re.S)
assert "<Polygonart>2</Polygonart>" in t
# Pipe S1 begins as in the official 2017 sample: at S1's floor point (SMP, 18 cm off the cover
# point that places S1), then the pipe's start at the shaft wall (RAP), 0.5 m along the pipe,
# 0.66 m from the cover point: seen from the cover, 8.7 degrees off the pipe's true 0 degrees.
seg = ("                <Kante>\n                  <Start>\n                    <Rechtswert>{}</Rechtswert>\n"
       "                    <Hochwert>{}</Hochwert>\n                  </Start>\n"
       "                  <Ende>\n                    <Rechtswert>{}</Rechtswert>\n"
       "                    <Hochwert>{}</Hochwert>\n                  </Ende>\n                </Kante>\n")
t = sub(t, "<Polygonart>3</Polygonart>\n              <Kante>\n                <Start>\n"
           "                  <Rechtswert>0.0</Rechtswert>\n                  <Hochwert>0.0</Hochwert>",
        "<Polygonart>3</Polygonart>\n" + seg.format(0.15, 0.10, 0.65, 0.10)
        + "              <Kante>\n                <Start>\n"
        "                  <Rechtswert>0.65</Rechtswert>\n                  <Hochwert>0.10</Hochwert>")
# Pipe S2 as the 2017 sample marks mouths: from S2's floor point (30.10, 0.05) along the channel,
# bending 45 degrees, to the pipe's start at the wall (RAP, 30.45, 0.40), straight to its end at
# S4's wall (RAP, 59.50, 0.40), then to S4. The slot's direction is the pipe's axis (0 degrees),
# not the channel's 45.
def point(tag, xy, attribute):
    mark = (f"                    <PunktattributAbwasser>{attribute}</PunktattributAbwasser>\n"
            if attribute else "")
    return (f"                  <{tag}>\n                    <Rechtswert>{xy[0]}</Rechtswert>\n"
            f"                    <Hochwert>{xy[1]}</Hochwert>\n{mark}                  </{tag}>\n")


def segment(a, b):  # (x, y, attribute) each
    return ("                <Kante>\n" + point("Start", a[:2], a[2]) + point("Ende", b[:2], b[2])
            + "                </Kante>\n")


line = [(30.10, 0.05, "SMP"), (30.45, 0.40, "RAP"), (59.50, 0.40, "RAP"), (60.0, 0.0, "SMP")]
s2_line = "<Polygonart>3</Polygonart>\n" + "".join(segment(a, b) for a, b in zip(line, line[1:]))
t = re.sub(r"(<KnotenZulauf>S2</KnotenZulauf>.*?)<Polygonart>3</Polygonart>\n.*?(\s*</Polygon>)",
           lambda m: m.group(1) + s2_line.rstrip("\n") + m.group(2), t, count=1, flags=re.S)
assert t.count("RAP") == 4
open("street-polyline.xml", "w", encoding="utf-8").write(t)

# --- Latin-1 ----------------------------------------------------------------------------------
t = base
t = sub(t, 'encoding="UTF-8"', 'encoding="ISO-8859-1"')
t = sub(t, "ISYBAU 2017-07 dialect;", "ISYBAU 2017-07 dialect, in ISO-8859-1 (Latin-1);")
t = t.replace("<Objektbezeichnung>S3</Objektbezeichnung>", "<Objektbezeichnung>Süd3</Objektbezeichnung>")
t = t.replace("<KnotenZulauf>S3</KnotenZulauf>", "<KnotenZulauf>Süd3</KnotenZulauf>")
t = t.replace("<Objektbezeichnung>S4</Objektbezeichnung>", "<Objektbezeichnung>Straße4</Objektbezeichnung>")
t = t.replace("<KnotenAblauf>S4</KnotenAblauf>", "<KnotenAblauf>Straße4</KnotenAblauf>")
t = t.replace("<KnotenZulauf>S4</KnotenZulauf>", "<KnotenZulauf>Straße4</KnotenZulauf>")
open("street-latin1.xml", "w", encoding="latin-1").write(t)

# --- Zustandsdaten ----------------------------------------------------------------------------


def record(station, code, ch1="", ch2="", q1=None, q2=None):
    out = ["          <RZustand>", f"            <Station>{station}</Station>",
           f"            <InspektionsKode>{code}</InspektionsKode>"]
    if ch1:
        out.append(f"            <Charakterisierung1>{ch1}</Charakterisierung1>")
    if ch2:
        out.append(f"            <Charakterisierung2>{ch2}</Charakterisierung2>")
    if q1 is not None:
        out.append(f"            <Quantifizierung1Numerisch>{q1}</Quantifizierung1Numerisch>")
    if q2 is not None:
        out.append(f"            <Quantifizierung2Numerisch>{q2}</Quantifizierung2Numerisch>")
    out.append("          </RZustand>")
    return "\n".join(out)


def inspected(name, kind, date, direction, records):
    rohr = (f"        <Rohrleitung>\n          <Inspektionsrichtung>{direction}</Inspektionsrichtung>\n"
            "        </Rohrleitung>\n") if direction else ""
    return (f"      <InspizierteAbwassertechnischeAnlage>\n"
            f"        <Objektbezeichnung>{name}</Objektbezeichnung>\n"
            f"        <Anlagentyp>{kind}</Anlagentyp>\n"
            f"        <OptischeInspektion>\n          <Inspektionsdatum>{date}</Inspektionsdatum>\n"
            + rohr.replace("\n        ", "\n          ").replace("        <Rohrleitung>", "          <Rohrleitung>")
            + "          <Inspektionsdaten>\n" + "\n".join("  " + r.replace("\n", "\n  ") for r in records)
            + "\n          </Inspektionsdaten>\n        </OptischeInspektion>\n"
            "      </InspizierteAbwassertechnischeAnlage>\n")


objects = [
    # Pipe S1 (30 m), with the flow: stations are offsets from S1.
    inspected("S1", 1, "2021-05-04", "O", [
        record("0.00", "BCD", "A"),
        record("7.50", "BBA", "B", "", 10),
        record("12.00", "BAJ", "B", "", 20),
        record("30.00", "BCE", "A")]),
    # An older inspection of S1: superseded by the one above.
    inspected("S1", 1, "2015-03-01", "O", [record("5.00", "BBC", "A", "", 40)]),
    # Pipe S3 (44.72 m), against the flow (from S2): offset = 44.72 - station.
    inspected("S3", 1, "2021-05-05", "U", [
        record("4.72", "BAA", "A", "", 50),
        record("20.00", "BBB", "A", "", 15)]),
    # Pipe S2 (30 m), with the flow: a collapse at 18 m.
    inspected("S2", 1, "2021-05-06", "O", [record("18.00", "BAC", "C")]),
    # Manhole S2 (Anlagentyp 3): not a pipe; left out.
    inspected("S2", 3, "2021-05-06", "", [record("0.5", "DAB", "A")]),
    # A lateral's inspection, named like no Haltung of the map: left out with a warning.
    inspected("X9", 1, "2021-05-06", "O", [record("1.00", "BBE", "A", "", 30)]),
]
z = ('<?xml version="1.0" encoding="UTF-8"?>\n'
     "<!-- sewerplan ISYBAU fixture: Zustandsdaten (inspection findings) for street-2017.xml, written\n"
     "     for sewerplan's tests (MIT). Findings: datasets/isybau/README.md. -->\n"
     '<Identifikation xmlns="http://www.ofd-hannover.la/Identifikation">\n'
     "  <Version>2017-07</Version>\n  <Datenkollektive>\n    <Zustandsdatenkollektiv>\n"
     + "".join(objects) + "    </Zustandsdatenkollektiv>\n  </Datenkollektive>\n</Identifikation>\n")
open("street-zustand.xml", "w", encoding="utf-8").write(z)
