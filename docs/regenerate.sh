#!/bin/sh
# Regenerates every committed figure and table under docs/figures (docs/guide.md): the seed
# paper's validation rerun (docs/joint-studies.md) and accuracy against run time
# (docs/accuracy.md). 10 s + 171 s wall (5 + 87 s CPU) on the 2-core machine at load average
# 5.3-6.2 (2026-11-25); run from the repository root after building.
set -e
cd "$(dirname "$0")/.."
build/bin/nmm-joint-study docs/figures --data data
build/bin/nmm-study docs/figures --data data
echo "docs/figures regenerated; copy changed tables into docs/joint-studies.md and docs/accuracy.md"
