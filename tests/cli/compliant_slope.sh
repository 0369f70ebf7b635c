#!/usr/bin/env bash
# compliant_slope.sh SOLVE MESH WORKDIR VARIANT SCENE CHECK
# The shaking slope of data/shaking_slope.json on a compliant base with absorbing sides
# (docs/staged-analysis.md, data/variants/shaking_slope_compliant.json), staged as UDEC does it:
#   1. settle: the scene as it is (base held by its support), DDA static, 20 steps of 5 ms, to
#      t = 0.1 s, where the shaking starts;
#   2. shake: from that checkpoint, the support and the base acceleration replaced by an
#      absorbing base bringing the same earthquake in (v_in = ½·∫a dt) and absorbing sides
#      letting in the same free-field motion; 550 steps to 1.2 s, with --pictures.
# Checks: the block slides by the rigid-block Newmark displacement within 5 % and stops
# (CHECK: tests/cli/check_shaking_slope.py, on stage 2's history); the base moves with the
# outcrop, ∫2·v_in dt = 0.1194 m, within 2 %; nothing moves before the wave (the carried
# static reaction: < 1 µm over the first step); the run ends at rest; energy.csv has the
# absorbed column, the dashpots took energy out, and W − D − A − ΔE stays within 1e-4 of A;
# summary.json lists "absorbing"; result.svg is drawn.
set -u
solve=$1 mesh=$2 dir=$3 variant=$4 scene=$5 check=$6
rm -rf "$dir" && mkdir -p "$dir"
"$solve" "$mesh" -o "$dir/settle" -q --set solver.dynamic=false --set solver.time_step=0.005 \
  --set solver.steps=20 || { echo "settling failed"; exit 1; }
"$solve" "$mesh" -o "$dir/shake" -q --pictures --restart "$dir/settle/checkpoint.nmmstate" \
  --config "$variant" --set solver.history_every=1 || { echo "shaking failed"; exit 1; }
python3 "$check" "$scene" "$dir/shake/history.csv" || exit 1
python3 - "$dir/shake" <<'PY'
import csv, json, math, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(f"{d}/history.csv")))
base = [(float(r["time"]), float(r["ux"]), float(r["uy"])) for r in rows if r["point"] == "1"]
t0 = base[0][0]
first = max(math.hypot(ux - base[0][1], uy - base[0][2]) for t, ux, uy in base if t <= t0 + 0.0021)
outcrop = 0.5 * 3 * 0.5 / (2 * math.pi) * 2 * 0.5  # ∫ 2·v_in dt over the pulse, m
end = base[-1][1]
s = json.load(open(f"{d}/summary.json"))
e = list(csv.DictReader(open(f"{d}/energy.csv")))[-1]
absorbed, residual, work = float(e["absorbed"]), float(e["residual"]), float(e["load_work"])
print(f"compliant base: moved {first:.2e} m in the first step, base at the end {end:.5f} m (outcrop {outcrop:.5f}, "
      f"{100 * (end / outcrop - 1):+.2f} %); absorbed {absorbed:.4g} J/m of {work:.4g} brought in, residual "
      f"{residual:.3g} J/m; {s['equilibrium']['verdict']}; effects {s['effects']}")
ok = first < 1e-6 and abs(end / outcrop - 1) < 0.02 and s["equilibrium"]["verdict"] == "at_rest"
ok &= absorbed > 0 and abs(residual) < 1e-4 * absorbed and "absorbing" in s["effects"]
ok &= "<polygon" in open(f"{d}/result.svg").read()
sys.exit(0 if ok else 1)
PY
