#!/usr/bin/env python3
"""nmm-inspect --network on data/dfn_slope.json's mesh: the JSON report names both generated sets
with their requested P21 (0.15, 0.12) and a measured P21 near it, the block count equals the
mesh's, block areas add up to the mesh area; the four SVGs parse as XML and show what they claim
(a rose per set, a histogram series per set, the block CDF, every joint of each set).
Usage: check_network_inspect.py REPORT.json SVG_PREFIX"""
import json
import sys
import xml.etree.ElementTree as ET

NS = "{http://www.w3.org/2000/svg}"
report = json.load(open(sys.argv[1]))
prefix = sys.argv[2]
net = report["network"]
sets = {s["name"]: s for s in net["joint_sets"]}
assert set(sets) == {"bedding", "cross"}, sets.keys()
for name, p21 in (("bedding", 0.15), ("cross", 0.12)):
    s = sets[name]
    assert s["generated"] and abs(s["requested_p21"] - p21) < 1e-12, s
    # One realisation over 2150 m²: within a factor of 2 (the 5 % check is in the unit tests).
    assert 0.5 * p21 < s["measured_p21"] < 2 * p21, s
    assert s["trace_length"]["count"] > 10 and s["p10"] > 0, s
assert net["blocks"]["count"] == report["blocks"], (net["blocks"], report["blocks"])
assert abs(net["blocks"]["total_area"] - report["area"]) < 1e-6 * report["area"]
pct = net["blocks"]["area_percentiles"]
assert pct["p0"] <= pct["p10"] <= pct["p50"] <= pct["p90"] <= pct["p100"], pct

def svg(kind):
    root = ET.parse(f"{prefix}-{kind}.svg").getroot()  # raises if not well-formed
    assert root.tag == NS + "svg", root.tag
    return root, "".join(t.text or "" for t in root.iter(NS + "text"))

root, text = svg("rose")
assert "set bedding" in text and "set cross" in text, text
assert len(root.findall(f".//{NS}polygon")) >= 2 + 2 * 2  # two rims, at least a wedge pair each
root, text = svg("trace-lengths")
assert f"set bedding ({sets['bedding']['trace_length']['count']} joints)" in text, text
assert f"set cross ({sets['cross']['trace_length']['count']} joints)" in text, text
root, text = svg("block-areas")
assert f"({report['blocks']} blocks)" in text, text
root, text = svg("network")
for name in sets:
    assert f"set {name}: {sets[name]['trace_length']['count']} joints" in text, text
paths = root.findall(f".//{NS}path")
assert len(paths) >= 2, len(paths)
for p in paths[-2:]:  # one path of segments per set: 'M x y L x y' per joint
    pass
moves = sum(p.get("d", "").count("M") for p in paths)
total = sum(s["trace_length"]["count"] for s in sets.values())
assert moves == total, (moves, total)
print("network report and pictures ok:", {n: round(s["measured_p21"], 4) for n, s in sets.items()},
      net["blocks"]["count"], "blocks")
