#!/usr/bin/env bash
# bolted_tunnel.sh SOLVE MESH WORKDIR REPORT VARIANT
# The tunnel of data/tunnel.json bolted after its excavation (docs/staged-analysis.md, "Stage
# 3: bolting"), shortened: consolidation (40 steps); excavation released over 20 steps, of
# which 10 run before the bolts go in; then from that checkpoint 50 more steps without bolts,
# and 50 with the 12 grouted bolts of VARIANT added at the restart (--config), with --pictures.
# Checks: the bolts are installed at the restart's step (50) carrying nothing from before; each
# ends in tension, none yields, and its force peaks inside the rock, not at the wall (the
# neutral point of a grouted bolt in converging rock: the grout pulls the bolt toward the
# opening near the wall and holds it back deeper, bond_force changing sign along it); the crown
# and the side wall converge less with the bolts than without; summary.json lists "bolts";
# bolts.csv has each bolt's 8 points at every output step; result.svg draws them (its legend
# names their largest force) and nmm-report redraws the same picture byte for byte. A bolt
# whose point lies in the excavated core is bad input: exit status 2, one line naming it.
set -u
solve=$1 mesh=$2 dir=$3 report=$4 variant=$5
rm -rf "$dir" && mkdir -p "$dir"
"$solve" "$mesh" -o "$dir/stage1" -q --set solver.steps=40 || { echo "stage 1 failed"; exit 1; }
"$solve" "$mesh" -o "$dir/stage2" -q --restart "$dir/stage1/checkpoint.nmmstate" --set 'excavate=[1]' \
  --set solver.excavation_steps=20 --set solver.steps=10 || { echo "stage 2 failed"; exit 1; }
"$solve" "$mesh" -o "$dir/plain" -q --restart "$dir/stage2/checkpoint.nmmstate" \
  --set solver.excavation_steps=20 --set solver.steps=50 || { echo "stage 3 without bolts failed"; exit 1; }
"$solve" "$mesh" -o "$dir/bolted" -q --pictures --restart "$dir/stage2/checkpoint.nmmstate" \
  --set solver.excavation_steps=20 --set solver.steps=50 --config "$variant" || { echo "stage 3 with bolts failed"; exit 1; }
cp "$dir/bolted/result.svg" "$dir/bolted_solve_result.svg"
"$report" "$dir/bolted" --quiet || { echo "nmm-report failed"; exit 1; }
cmp -s "$dir/bolted/result.svg" "$dir/bolted_solve_result.svg" || { echo "nmm-report drew another picture"; exit 1; }
"$solve" "$mesh" -o "$dir/bad" -q --restart "$dir/stage2/checkpoint.nmmstate" \
  --set 'bolts=[{"points": [[20, 20], [20, 25]], "type": "anchored", "stiffness": 1e7}]' 2> "$dir/bad.err"
status=$?
echo "a bolt from the excavated core: exit $status: $(cat "$dir/bad.err")"
[ $status -eq 2 ] && [ "$(wc -l < "$dir/bad.err")" -eq 1 ] && grep -q "/bolts/0/points: its end (20, 20) lies outside the rock" "$dir/bad.err" ||
  { echo "expected exit status 2 and one line naming /bolts/0/points"; exit 1; }
python3 - "$dir" <<'PY'
import csv, json, sys
d = sys.argv[1]
def last(stage):
    rows = list(csv.DictReader(open(f"{d}/{stage}/history.csv")))
    step = max(int(r["step"]) for r in rows)
    return {int(r["point"]): (float(r["ux"]), float(r["uy"])) for r in rows if int(r["step"]) == step}
plain, bolted = last("plain"), last("bolted")
s = json.load(open(f"{d}/bolted/summary.json"))
bolts = s["bolts"]
rows = list(csv.DictReader(open(f"{d}/bolted/bolts.csv")))
end = max(int(r["step"]) for r in rows)
ok = len(bolts) == 12 and "bolts" in s["effects"]
ok &= all(b["installed_step"] == 50 and not b["yielded"] and not b["broken"] and b["max_axial_force"] > 0 for b in bolts)
steps = sorted({int(r["step"]) for r in rows})
ok &= all(sum(1 for r in rows if int(r["step"]) == st) == 12 * 8 for st in steps) and steps[0] == 50
first = [float(r["axial_force"]) for r in rows if int(r["step"]) == 50]
ok &= all(f == 0 for f in first)  # installed now: nothing of the rock's earlier motion
inside = 0
for b in range(12):
    line = [r for r in rows if int(r["step"]) == end and int(r["bolt"]) == b]
    forces = [float(r["axial_force"]) for r in line]
    bond = [float(r["bond_force"]) for r in line]
    peak = max(range(len(forces)), key=lambda i: forces[i])
    inside += 0 < peak < len(forces) - 1 and min(forces) >= 0 and bond[0] < 0 < bond[-1]
crown = (plain[0][1], bolted[0][1]); wall = (plain[2][0], bolted[2][0])
print(f"bolted tunnel: crown uy {crown[0]:.6e} m without bolts, {crown[1]:.6e} m with; side wall ux {wall[0]:.6e} / "
      f"{wall[1]:.6e} m; bolt forces up to {max(b['max_axial_force'] for b in bolts):.0f} N, peaking inside the rock "
      f"on {inside} of 12; {len(steps)} output steps in bolts.csv")
ok &= inside == 12 and abs(crown[1]) < abs(crown[0]) and abs(wall[1]) < abs(wall[0])
svg = open(f"{d}/bolted/result.svg").read()
ok &= "bolts: axial force" in svg
sys.exit(0 if ok else 1)
PY
