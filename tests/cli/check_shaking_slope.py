#!/usr/bin/env python3
"""check_shaking_slope.py SCENE HISTORY_CSV

Checks the outcome data/shaking_slope.json promises: the block stands before the shaking
(< 1 mm), slides down the slope by the rigid-block Newmark displacement within 5 %, and has
stopped by the end. The Newmark reference is integrated here from the scene's own time table,
slope and friction (docs/physics.md §5):
    s'' = a cos α + g sin α − tan φ (g cos α − a sin α)   while s' > 0 (or the right side > 0)
with a(t) the ground acceleration in x (+x drives the block down the slope, which falls to −x).
"""
import csv, json, math, re, sys

scene_text = open(sys.argv[1]).read()
scene = json.loads(re.sub(r"^\s*//.*$", "", scene_text, flags=re.M))
table = scene["base_acceleration"]["x"]
phi = math.radians(scene["joint_sets"]["interface"]["friction_deg"])
g = -scene["gravity"][1]
b = scene["bodies"][1]["outer"]
alpha = math.atan2(b[1][1] - b[0][1], b[1][0] - b[0][0])


def accel(t):
    if t <= table[0][0]:
        return table[0][1]
    for (t0, v0), (t1, v1) in zip(table, table[1:]):
        if t <= t1:
            return v0 + (v1 - v0) * (t - t0) / (t1 - t0)
    return table[-1][1]


rows = {}
for r in csv.DictReader(open(sys.argv[2])):
    rows.setdefault(float(r["time"]), {})[int(r["point"])] = (float(r["ux"]), float(r["uy"]))
times = sorted(rows)
t_end = times[-1]
down = (-math.cos(alpha), -math.sin(alpha))


def slid(t):
    (bx, by), (gx, gy) = rows[t][0], rows[t][1]
    return (bx - gx) * down[0] + (by - gy) * down[1]


v = s = 0.0
dt = 1e-5
t = 0.0
while t < t_end:
    a = accel(t + 0.5 * dt)
    drive = a * math.cos(alpha) + g * math.sin(alpha) - math.tan(phi) * (g * math.cos(alpha) - a * math.sin(alpha))
    if v > 0 or drive > 0:
        v = max(0.0, v + drive * dt)
        s += v * dt
    t += dt

before = max(abs(slid(t)) for t in times if t <= table[1][0] + 1e-9)
final = slid(times[-1])
late = [t for t in times if t >= t_end - 0.2]
drift = abs(slid(late[-1]) - slid(late[0]))
print(f"slope {math.degrees(alpha):.2f} deg, friction {math.degrees(phi):.1f} deg: before the shaking "
      f"{before:.2e} m, slid {final:.5f} m, rigid-block Newmark {s:.5f} m ({100 * (final - s) / s:+.2f} %), "
      f"last 0.2 s {drift:.2e} m")
ok = before < 1e-3 and abs(final - s) < 0.05 * s and drift < 1e-3 * s and s > 0.01
sys.exit(0 if ok else 1)
