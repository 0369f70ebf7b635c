#!/usr/bin/env bash
# large_mesh_talks.sh PREPROCESS SCENE WORKDIR
# nmm-preprocess on a mesh far beyond the documented sizes (docs/preprocess.md, "Large meshes"):
# before cutting it must warn (`/mesh/size: warning: about N triangles ...`, from 5e5 triangles)
# and report its first stage ("cutting covers", from 2e4 triangles) — the user learns at once
# that the cut will take minutes. The cut itself is not waited for: the process is stopped as
# soon as both lines are out, and no mesh file may be left (none is ever half-written).
set -u
pre=$1 scene=$2 dir=$3
rm -rf "$dir" && mkdir -p "$dir"
# Mesh size 0.03 m over the tunnel's 40 m × 40 m window: about 4e6 triangles.
"$pre" "$scene" -o "$dir/big.nmm" --set mesh.size=0.03 2>"$dir/err" >/dev/null &
pid=$!
i=0
until grep -q "cutting covers" "$dir/err" 2>/dev/null || [ $i -ge 600 ]; do sleep 0.05; i=$((i + 1)); done
kill "$pid" 2>/dev/null; wait "$pid" 2>/dev/null
cat "$dir/err"
fail=0
grep -q "/mesh/size: warning: about 4.[0-9]*e+06 triangles at mesh size 0.03 m" "$dir/err" || { echo "no size warning"; fail=1; }
grep -q "^nmm-preprocess: cutting covers (about 4.[0-9]*e+06 triangles)" "$dir/err" || { echo "no stage line"; fail=1; }
ls "$dir"/big.nmm* >/dev/null 2>&1 && { echo "a mesh file was left: $(ls "$dir"/big.nmm*)"; fail=1; }
exit $fail
