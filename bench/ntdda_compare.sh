#!/bin/sh
# nmm beside a DDA code (ntdda, open 2D DDA in C) on the same staggered brick walls, static and
# dynamic, the first 100 steps, CPU per step on one thread each (docs/performance.md "Against a
# DDA code"). Not part of CI: the DDA side is a program you build yourself, outside this
# repository, from its public sources; give its runner and its wall generator:
#
#   NTDDA_RUN=/path/to/ntdda_run GEN_WALL=/path/to/gen_wall.py [MESHES="0.5 2"] sh bench/ntdda_compare.sh [SIZES]
#
# NTDDA_RUN is called as `ntdda_run WALL.geo WALL.ana` and prints a line
# `NTDDA blocks=… ms_per_step=…` on stderr; GEN_WALL writes those files for an NX × NY wall
# (`gen_wall.py OUTDIR NX NY --steps S`; E = 10 MPa, penalty 50·E, φ = 30°, Δt = 1 ms), which
# this script switches to SI units and, for the static rows, to static analysis. The nmm side is
# reference/brick_wall.h peer_wall (the same wall) run by contact_bench --peer at each mesh size
# of MESHES (m, default "0.5 2": about 22 unknowns per brick, and about 9 — a mesh coarser than
# the bricks, where a brick lies in one or two triangles, as near DDA's 6 as NMM's covers come).
# SIZES: wall sizes, default "10 20 30". Writes bench/results/peer_compare.csv (one row per wall,
# mode and mesh size: both codes' ms per step, nmm's counts) from the repository root, after
# building. Both sides are CPU time: nmm's is the thread's CPU over its 100 steps (contact_bench);
# the DDA code's is its process's user + system time (/usr/bin/time) over the run, cutting
# included, per step. The runner's own ms_per_step is wall-clock (CLOCK_MONOTONIC), which on a
# loaded machine counts the time it waited: it is kept beside it (ntdda_wall_ms_per_step). Each
# row also names the CPU and the BLAS kernels (build nmm-solve too: its --version gives them).
set -e
cd "$(dirname "$0")/.."
: "${NTDDA_RUN:?set NTDDA_RUN to the DDA code's runner}"
: "${GEN_WALL:?set GEN_WALL to the wall generator}"
SIZES=${1:-"10 20 30"}
MESHES=${MESHES:-"0.5 2"}
STEPS=100
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
out=bench/results/peer_compare.csv
# The machine each row ran on: the CPU's model name and the BLAS kernels OpenBLAS picked for it
# (nmm-solve --version's BLAS line, summary.json's `blas`; commas become semicolons).
cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1 | tr ',' ';')
blas=$( (build/bin/nmm-solve --version 2>/dev/null || true) | sed -n 's/^BLAS: //p' | tr ',' ';')
echo "date,mode,wall_n,nmm_mesh_size,ntdda_blocks,ntdda_ms_per_step,nmm_blocks,nmm_unknowns,nmm_ms_per_step,ratio,nmm_solves_per_step,nmm_factorisations_per_step,nmm_cg_per_step,nmm_detection_ms_per_step,nmm_cuts,load_average,ntdda_wall_ms_per_step,nmm_analyses,cpu,blas" > "$out"
for n in $SIZES; do
  for h in $MESHES; do
    build/bin/contact_bench --peer --sizes "$n" --steps $STEPS --mesh "$h" --csv "$work/nmm_$n.part" > /dev/null
    tail -n +2 "$work/nmm_$n.part" >> "$work/nmm_$n.csv"
  done
  for mode in static dynamic; do
    d="$work/$mode$n"
    python3 "$GEN_WALL" "$d" "$n" "$n" --steps $STEPS > /dev/null
    sed -i 's|<Unitmass> 2.5 </Unitmass> <Unitweight> 24.525 </Unitweight>|<Unitmass> 2500 </Unitmass> <Unitweight> 24525 </Unitweight>|' "$d/wall.ana"
    [ "$mode" = static ] && sed -i 's|<Analysistype type="dynamic"/>|<Analysistype type="static"/>|' "$d/wall.ana"
    (cd "$d" && ulimit -f 1000000 && /usr/bin/time -f 'NTDDA_CPU %U %S' timeout 600 "$NTDDA_RUN" wall.geo wall.ana \
       > /dev/null 2> run.txt) || true
    line=$(grep '^NTDDA ' "$d/run.txt" || true)
    nt_blocks=$(echo "$line" | sed -n 's/.*blocks=\([0-9]*\).*/\1/p')
    nt_wall=$(echo "$line" | sed -n 's/.*ms_per_step=\([0-9.]*\).*/\1/p')
    nt_steps=$(echo "$line" | sed -n 's/.*steps=\([0-9]*\)\/.*/\1/p')
    nt_ms=$(awk -v s="$nt_steps" '/^NTDDA_CPU/ && s > 0 { printf "%.4f", ($2 + $3) * 1000 / s }' "$d/run.txt")
    # contact_bench --peer: mode,wall_n,mesh_size,blocks,unknowns,contacts,steps,cpu_ms_per_step,
    # solves_per_step,factorisations_per_step,cg_per_step,friction_updates_per_step,
    # detection_ms_per_step,factorisation_ms_per_step,cg_ms_per_step,cuts,status,load_average,
    # threads,wall_ms_per_step,line_search_ms_per_step,assembly_ms_per_step,update_ms_per_step,analyses
    grep "^$mode," "$work/nmm_$n.csv" | awk -F, -v d="$(date +%F)" -v nb="$nt_blocks" -v nm="$nt_ms" -v nw="$nt_wall" \
        -v cpu="$cpu" -v blas="$blas" '{
      ratio = (nm > 0) ? sprintf("%.2f", $8 / nm) : "";
      printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", d, $1, $2, $3, nb, (nm == "" ? "crashed" : nm), $4, $5, $8, ratio, $9, $10, $11, $13, $16, $18, nw, $24, cpu, blas }' >> "$out"
  done
done
cat "$out"
