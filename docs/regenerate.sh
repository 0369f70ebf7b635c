#!/bin/sh
# Regenerates every committed figure and table under docs/figures (docs/guide.md): the seed
# paper's validation rerun (docs/joint-studies.md) and accuracy against run time
# (docs/accuracy.md). 10 s + 171 s wall (5 + 87 s CPU) on the 2-core machine at load average
# 5.3-6.2 (2026-11-25); nmm-study with its fracture cases 392 s wall (89 s CPU) at load average
# about 20 (2026-11-30). Run from the repository root after building.
set -e
cd "$(dirname "$0")/.."
build/bin/nmm-joint-study docs/figures --data data
# Prescott: the kernels every x86-64 CPU runs, as CTest study.accuracy_quick (docs/accuracy.md).
OPENBLAS_CORETYPE=Prescott build/bin/nmm-study docs/figures --data data
# The doc pages carry copies of these tables: their rows follow the fresh ones.
python3 docs/sync_tables.py docs/figures/joint_studies_tables.md docs/joint-studies.md
python3 docs/sync_tables.py docs/figures/accuracy_tables.md docs/accuracy.md
# The fracturing examples' pictures (docs/fracture.md): about 8 s.
tmp=$(mktemp -d)
for s in brazilian_disc step_path_slope; do
  build/bin/nmm-preprocess data/$s.json -o "$tmp/$s.nmm" > /dev/null
  build/bin/nmm-solve "$tmp/$s.nmm" -o "$tmp/$s" --pictures --quiet
  cp "$tmp/$s/result.svg" docs/figures/$s.svg
done
rm -rf "$tmp"
