#!/usr/bin/env python3
"""Prints the facts of a result.svg a test compares, one per line:
   polygons N          filled element polygons (the colour bar's bands excluded)
   bar LO HI           the colour bar's end labels
   sliding N / sticking N   contacts in the legend (or "state not recorded")
Usage: picture_facts.py RESULT.svg"""
import re
import sys

svg = open(sys.argv[1], encoding="utf-8").read()
print("polygons", len(re.findall(r"<polygon ", svg)))
labels = re.findall(r"<text[^>]*>([-+0-9.e]+)</text>", svg)
if len(labels) >= 5:
    print("bar", labels[0], labels[4])
for state in ("sliding", "sticking"):
    m = re.search(state + r": (\d+) contacts", svg)
    print(state, m.group(1) if m else "none")
if "contact state not recorded" in svg:
    print("state not recorded")
