#!/usr/bin/env bash
# staged_tunnel.sh SOLVE MESH WORKDIR
# The staged tunnel analysis of data/tunnel.json (docs/staged-analysis.md), shortened:
#   1. consolidation (40 steps): the model in in-situ equilibrium barely moves (< 1 mm);
#   2. excavation from stage 1's checkpoint (--set excavate=[1], released over 20 steps, 60
#      steps): the crown moves down, the invert up, the side wall in, each by more than stage 1
#      moved it; step numbers continue from the checkpoint;
#   3. the joint-law variant (Bandis–Barton, hyperbolic) from stage 2's checkpoint (10 steps).
# Pictures (issue 13): stages 1 and 2 run with --pictures; stage 2's result.svg leaves the
# excavated core out (as many fewer element polygons as the core has elements, the legend says
# "excavated"), summary.json lists it in excavated_bodies, and nmm-report redraws the same picture.
# Usage: staged_tunnel.sh SOLVE MESH WORKDIR [INSPECT REPORT]
set -u
solve=$1 mesh=$2 dir=$3 inspect=${4:-} report=${5:-}
rm -rf "$dir" && mkdir -p "$dir"
"$solve" "$mesh" -o "$dir/stage1" -q --pictures --set solver.steps=40 || { echo "stage 1 failed"; exit 1; }
"$solve" "$mesh" -o "$dir/stage2" -q --pictures --restart "$dir/stage1/checkpoint.nmmstate" \
  --set 'excavate=[1]' --set solver.steps=60 --set solver.excavation_steps=20 || { echo "stage 2 failed"; exit 1; }
if [ -n "$inspect" ]; then
  "$inspect" "$mesh" --json --full > "$dir/mesh.json" || { echo "nmm-inspect failed"; exit 1; }
  cp "$dir/stage2/result.svg" "$dir/stage2_solve_result.svg"
  "$report" "$dir/stage2" --quiet || { echo "nmm-report failed"; exit 1; }
  cmp -s "$dir/stage2/result.svg" "$dir/stage2_solve_result.svg" || { echo "nmm-report drew another picture of stage 2"; exit 1; }
fi
"$solve" "$mesh" -o "$dir/stage3" -q --restart "$dir/stage2/checkpoint.nmmstate" --set solver.steps=10 \
  --set joint_sets.foliation.normal.model=bandis_barton --set joint_sets.foliation.shear.model=hyperbolic \
  --set joint_sets.cross.normal.model=bandis_barton --set joint_sets.cross.shear.model=hyperbolic ||
  { echo "stage 3 failed"; exit 1; }
python3 - "$dir" <<'PY'
import csv, json, sys
d = sys.argv[1]
def last(stage):
    rows = list(csv.DictReader(open(f"{d}/{stage}/history.csv")))
    step = max(int(r["step"]) for r in rows)
    return step, {int(r["point"]): (float(r["ux"]), float(r["uy"])) for r in rows if int(r["step"]) == step}, rows
s1, u1, _ = last("stage1")
s2, u2, rows2 = last("stage2")
s3, u3, _ = last("stage3")
ok = True
moved1 = max(abs(c) for p in u1.values() for c in p)
print(f"stage 1 (consolidation, {s1} steps): largest wall-point displacement {moved1:.2e} m")
ok &= moved1 < 1e-3
first2 = min(int(r["step"]) for r in rows2)
print(f"stage 2 starts at step {first2} (stage 1 ended at {s1}), ends at {s2}")
ok &= first2 == s1
crown = u2[0][1] - u1[0][1]; invert = u2[1][1] - u1[1][1]; wall = u2[2][0] - u1[2][0]
print(f"stage 2 (excavation): crown {crown:+.3e} m, invert {invert:+.3e} m, side wall {wall:+.3e} m")
ok &= crown < -2e-4 and invert > 1e-4 and wall < -5e-5
ok &= -crown > 5 * moved1 and invert > 5 * moved1
import os
if os.path.exists(f"{d}/mesh.json"):
    core = sum(1 for e in json.load(open(f"{d}/mesh.json"))["elements"] if e["body"] == 1)
    n1, n2 = (open(f"{d}/{s}/result.svg").read().count("<polygon") for s in ("stage1", "stage2"))
    exc = json.load(open(f"{d}/stage2/summary.json")).get("excavated_bodies")
    legend = "excavated (dashed grey, not drawn): body 1" in open(f"{d}/stage2/result.svg").read()
    print(f"pictures: stage 1 {n1} polygons, stage 2 {n2} (the core has {core} elements); "
          f"excavated_bodies {exc}; legend names it: {legend}")
    ok &= core > 0 and n1 - n2 == core and legend and exc == [{"body": 1, "step": s1}]
eff = json.load(open(f"{d}/stage3/summary.json"))["effects"]
print(f"stage 3 (joint laws): {s3} steps, effects {eff}")
ok &= "bandis_barton" in eff and "hyperbolic" in eff and "excavation" in eff
sys.exit(0 if ok else 1)
PY
