#!/usr/bin/env bash
# install_tree.sh BUILD_DIR PREFIX
# `cmake --install BUILD_DIR --prefix PREFIX`, then uses the installed tools the way a user with
# PREFIX/bin on PATH does, from a folder outside the source and build trees: the example scene
# cut and run, and a sweep through Snakemake, which must use the installed workflow
# (PREFIX/share/nmm/workflow/Snakefile, found relative to the installed nmm-sweep), not the
# source tree's. The installed Snakefile gets an onstart handler that prints a marker, and the
# sweep's snakemake.log must show it. The Python module, when built, is imported from PREFIX.
set -euo pipefail
build=$1 prefix=$2
rm -rf "$prefix"
cmake --install "$build" --prefix "$prefix" >/dev/null
for tool in nmm-preprocess nmm-inspect nmm-solve nmm-report nmm-history-plot nmm-joint-study \
            nmm-study nmm-fos nmm-sweep; do
  [ -x "$prefix/bin/$tool" ] || { echo "not installed: bin/$tool"; exit 1; }
done
share=$prefix/share/nmm
for f in workflow/Snakefile workflow/profiles/slurm/config.yaml data/jointed_slope.json \
         data/sweeps/incline_friction.json; do
  [ -f "$share/$f" ] || { echo "not installed: share/nmm/$f"; exit 1; }
done
[ -f "$prefix/share/doc/nmm/docs/guide.md" ] || { echo "not installed: share/doc/nmm/docs/guide.md"; exit 1; }
[ ! -e "$prefix/share/doc/nmm/docs/notes" ] || { echo "installed: share/doc/nmm/docs/notes (the developers' journal is not for users)"; exit 1; }
printf '\nonstart:\n    print("nmm install test: the installed Snakefile")\n' >>"$share/workflow/Snakefile"

work=$prefix/work
mkdir -p "$work"
cd "$work"
export PATH=$prefix/bin:$PATH
nmm-preprocess "$share/data/block_on_incline.json" -o incline.nmm -q
nmm-solve incline.nmm -o incline_run --quiet --set solver.steps=5
[ -s incline_run/summary.json ] || { echo "no incline_run/summary.json"; exit 1; }
nmm-sweep "$share/data/sweeps/incline_friction.json" -o sweep --engine snakemake --workers 2 \
          --set solver.steps=3 --set solver.output_every=1
ok=$(grep -c ',0,ok,' sweep/sweep.csv)
[ "$ok" = 6 ] || { echo "sweep: $ok of 6 runs ok"; exit 1; }
grep -q "nmm install test: the installed Snakefile" sweep/snakemake.log ||
  { echo "the sweep did not run the installed Snakefile (sweep/snakemake.log)"; exit 1; }
# The Python module (when built): installed into PREFIX's site-packages (a scratch prefix is
# not on sys.path: PYTHONPATH names it, as docs/python.md says), imported from there, and an
# installed example run against the installed scenes.
if [ -e "$build/python/nmm/__init__.py" ]; then
  site=$(ls -d "$prefix"/lib/python3*/site-packages)
  [ -f "$site/nmm/__init__.py" ] && ls "$site"/nmm/_nmm*.so >/dev/null ||
    { echo "not installed: the package nmm in $prefix/lib/python3*/site-packages"; exit 1; }
  # The module runs on the kernels OpenBLAS picked at import; nmm-solve may have chosen better
  # ones (summary.json blas.chosen, docs/performance.md *BLAS kernels*): the same bits need the
  # same family, as docs/python.md *Same answers* tells a user.
  # (`env` always: where nmm-solve kept OpenBLAS's own choice, as on an AMD EPYC, chosen is empty,
  # and an assignment after an expansion that vanished would be run as the command.)
  chosen=$("$build/bin/python3" -c "import json; print(json.load(open('incline_run/summary.json'))['blas'].get('chosen', ''))")
  env ${chosen:+OPENBLAS_CORETYPE=$chosen} PYTHONPATH=$site "$build/bin/python3" -c "
import nmm, sys
assert nmm.__file__.startswith('$site'), nmm.__file__
mesh = nmm.Mesh.load('incline.nmm')
s = nmm.Solver(mesh, set={'solver.steps': 5}); s.run()
import json; assert s.state_hash == json.load(open('incline_run/summary.json'))['state_hash']"
  PYTHONPATH=$site "$build/bin/python3" "$share/examples/python/friction_sweep.py" py >/dev/null
  [ -s py/friction_sweep.png ] || { echo "the installed example wrote no py/friction_sweep.png"; exit 1; }
fi
echo "installed into $prefix: tools run from $work, the sweep used the installed workflow"
