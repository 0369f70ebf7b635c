#!/usr/bin/env python3
"""Checks the Slurm profile of workflow/ for both Snakemake generations (CTest studies.slurm_profiles).

    check_profiles.py PROFILE_DIR SNAKEFILE

PROFILE_DIR holds config.yaml (Snakemake 7.x, built-in --slurm) and config.v8+.yaml (Snakemake >= 8,
executor plugin snakemake-executor-plugin-slurm). What is checked:
- both files are YAML mappings;
- Snakemake's own choice of file: >= 8 takes the config.vN+.yaml with the largest N <= its major
  version, 7.x reads config.yaml only (the rule of Snakemake 8's cli.get_profile_dir, re-stated
  below), so 7 gets config.yaml and 8, 9 get config.v8+.yaml;
- config.yaml: `slurm: true`, no `executor`; every key a long option of the installed Snakemake
  (from `snakemake --help`) when that is 7.x; then a dry run (`snakemake -n --profile`) of the
  Snakefile on a scratch job, which makes Snakemake 7 parse the profile for real;
- config.v8+.yaml: `executor: slurm`; every key an option of Snakemake 8 (the list below, from
  src/snakemake/cli.py of Snakemake 8/9) or a setting of the Slurm plugin (`slurm-` + a field of its
  ExecutorSettings); none of the 7.x cluster keys (slurm, cluster, cluster-config, cluster-status,
  drmaa), which Snakemake 8 rejects; `default-resources` a mapping of resources the plugin turns into
  sbatch options, runtime and mem_mb positive numbers (or a runtime with a unit, "2h");
- the Snakefile's rule resources are resources the plugin knows.
What is not checked: that Snakemake 8 and the plugin, installed, accept the file (not in Debian),
and a run through Slurm with them. Exit status 0 pass, 1 fail (one line per problem), 77 no PyYAML.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

try:
    import yaml
except ImportError:
    print("PyYAML (python3-yaml) is missing: skipped")
    sys.exit(77)

# Long options of Snakemake 8/9 (src/snakemake/cli.py), without the leading "--".
SNAKEMAKE8_OPTIONS = set("""
all-temp allow-ambiguity allowed-rules apptainer-args apptainer-prefix archive attempt batch
benchmark-extended cache cleanup-metadata cleanup-shadow conda-base-path conda-cleanup-envs
conda-cleanup-pkgs conda-create-envs-only conda-frontend conda-not-block-search-path-envvars
conda-prefix config configfile configfiles consider-ancient container-cleanup-images
container-image containerize cores d3dag dag debug debug-dag default-resources
default-storage-prefix default-storage-provider delete-all-output delete-temp-output
deploy-sources deployment-method detailed-summary directory draft-notebook drop-metadata dry-run
edit-notebook envvars executor export-cwl filegraph force force-use-threads forceall forcerun
generate-unit-tests greediness group-components groups ignore-incomplete immediate-submit
job-deploy-sources jobname jobs jobscript keep-going keep-incomplete keep-storage-local-copies
latency-wait lint list-changes list-conda-envs list-input-changes list-params-changes list-rules
list-target-rules list-untracked local-cores local-groupid local-storage-prefix logger
max-checksum-file-size max-inventory-time max-jobs-per-second max-jobs-per-timespan
max-status-checks-per-second max-threads mode no-hooks no-temp nocolor nolock
not-retrieve-storage notebook-listen omit-from persistence-backend precommand
preemptible-retries preemptible-rules print-compilation printshellcmds prioritize profile quiet
rerun-incomplete rerun-triggers report report-stylesheet resources restart-times retries
rulegraph runtime-profile scheduler scheduler-greediness scheduler-solver-path
seconds-between-status-checks set-resource-scopes set-resources set-scatter set-threads
shadow-prefix shared-fs-usage show-failed-logs singularity-args singularity-prefix
skip-script-cleanup snakefile software-deployment-method summary
target-files-omit-workdir-adjustment target-jobs touch trust-io-cache unlock until
use-apptainer use-conda use-envmodules use-singularity verbose wait-for-files
wait-for-files-file workflow-profile wrapper-prefix
""".split())

# snakemake-executor-plugin-slurm: its ExecutorSettings fields, given as --slurm-FIELD.
SLURM_PLUGIN_SETTINGS = {"slurm-" + s for s in (
    "logdir", "keep-successful-logs", "delete-logfiles-older-than",
    "init-seconds-before-status-checks", "requeue", "no-account")}

# Resources the plugin turns into sbatch options (its run_job): -A, -p, -t, --mem, --mem-per-cpu,
# -C, --clusters, --nodes, --ntasks, --cpus-per-task, --gres, extra flags.
SLURM_PLUGIN_RESOURCES = {
    "slurm_account", "slurm_partition", "runtime", "mem_mb", "mem_mb_per_cpu", "constraint",
    "clusters", "nodes", "tasks", "tasks_per_node", "mpi", "cpus_per_task", "gpu", "gres",
    "slurm_extra",
    # Snakemake's own standard resources, always present
    "mem", "disk", "disk_mb", "tmpdir", "_cores", "_nodes"}

# Keys of 7.x cluster execution that Snakemake 8 no longer has.
SNAKEMAKE7_ONLY = {"slurm", "cluster", "cluster-config", "cluster-status", "cluster-cancel",
                   "drmaa", "kubernetes", "tibanna", "google-lifesciences"}

# Snakemake 8's rule for the file of a profile folder (cli.get_profile_dir).
PROFILE_FILE = re.compile(r"(?P<main>profile|config)(?:\.v(?P<min_major>\d+)\+)?\.yaml")

problems = []


def fail(msg):
    problems.append(msg)


def chosen_file(files, major):
    if major < 8:  # 7.x: get_profile_file(profile, "config.yaml")
        return "config.yaml" if "config.yaml" in files else None
    best, best_major = None, -1
    for f in files:
        m = PROFILE_FILE.fullmatch(f)
        if not m:
            continue
        mm = int(m.group("min_major") or 0)
        if mm <= major and mm > best_major:
            best, best_major = f, mm
    return best


def load(path):
    try:
        with open(path) as f:
            doc = yaml.safe_load(f)
    except (OSError, yaml.YAMLError) as e:
        fail(f"{path}: {e}")
        return {}
    if not isinstance(doc, dict):
        fail(f"{path}: not a YAML mapping")
        return {}
    return doc


def positive_minutes(v):
    if isinstance(v, (int, float)) and not isinstance(v, bool):
        return v > 0
    return isinstance(v, str) and re.fullmatch(r"\d+(\.\d+)?\s*(s|m|min|h|d)", v.strip()) is not None


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    prof, snakefile = sys.argv[1], sys.argv[2]
    files = os.listdir(prof)
    for major, want in ((7, "config.yaml"), (8, "config.v8+.yaml"), (9, "config.v8+.yaml")):
        got = chosen_file(files, major)
        if got != want:
            fail(f"{prof}: Snakemake {major} would read {got}, not {want}")

    v7 = load(os.path.join(prof, "config.yaml"))
    v8 = load(os.path.join(prof, "config.v8+.yaml"))

    # Snakemake 7 profile.
    if v7.get("slurm") is not True:
        fail("config.yaml: `slurm: true` missing (Snakemake 7's built-in Slurm support)")
    if "executor" in v7:
        fail("config.yaml: `executor` is a Snakemake 8 key; 7.x rejects it")
    for item in v7.get("default-resources", []) or []:
        key = str(item).split("=", 1)[0]
        if key not in SLURM_PLUGIN_RESOURCES:
            fail(f"config.yaml: default resource {key!r} is not a Slurm resource")
    sm = shutil.which("snakemake")
    version = ""
    if sm:
        version = subprocess.run([sm, "--version"], capture_output=True, text=True).stdout.strip()
    if version.startswith("7."):
        help_text = subprocess.run([sm, "--help"], capture_output=True, text=True).stdout
        options = set(re.findall(r"--([a-z][a-z0-9-]*)", help_text))
        for key in v7:
            if key not in options:
                fail(f"config.yaml: {key!r} is not an option of Snakemake {version}")
        # A dry run: Snakemake parses the profile and plans the job (no sbatch call).
        with tempfile.TemporaryDirectory() as root:
            job = os.path.join(root, "runs", "check")
            os.makedirs(job)
            with open(os.path.join(job, "run.sh"), "w") as f:
                f.write("#!/bin/sh\necho '{\"exit\": 0}' > job_status.json\n")
            r = subprocess.run([sm, "-s", snakefile, "-d", root, "--profile", prof, "-n"],
                               capture_output=True, text=True)
            if r.returncode != 0 or "runs/check/job_status.json" not in r.stdout + r.stderr:
                fail(f"config.yaml: Snakemake {version} dry run failed: "
                     + (r.stderr.strip().splitlines() or ["?"])[-1])
            else:
                print(f"config.yaml: Snakemake {version} dry run with the profile: ok")
    else:
        print(f"Snakemake 7 not installed ({version or 'none'}): config.yaml checked statically only")

    # Snakemake 8 profile.
    if v8.get("executor") != "slurm":
        fail("config.v8+.yaml: `executor: slurm` missing")
    for key in v8:
        if key in SNAKEMAKE7_ONLY:
            fail(f"config.v8+.yaml: {key!r} is a Snakemake 7 key; Snakemake 8 rejects it")
        elif key not in SNAKEMAKE8_OPTIONS and key not in SLURM_PLUGIN_SETTINGS:
            fail(f"config.v8+.yaml: {key!r} is neither a Snakemake 8 option nor a Slurm plugin setting")
    res = v8.get("default-resources")
    if not isinstance(res, dict):
        fail("config.v8+.yaml: default-resources must be a mapping (resource: value)")
        res = {}
    for key, value in res.items():
        if key not in SLURM_PLUGIN_RESOURCES:
            fail(f"config.v8+.yaml: default resource {key!r} is not one the Slurm plugin uses")
    if not positive_minutes(res.get("runtime")):
        fail(f"config.v8+.yaml: runtime {res.get('runtime')!r} is not a positive time (minutes or '2h')")
    mem = res.get("mem_mb")
    if not (isinstance(mem, int) and not isinstance(mem, bool) and mem > 0):
        fail(f"config.v8+.yaml: mem_mb {mem!r} is not a positive integer")
    for key in ("jobs", "latency-wait", "slurm-init-seconds-before-status-checks"):
        if key in v8 and not (isinstance(v8[key], int) and v8[key] >= 0):
            fail(f"config.v8+.yaml: {key} {v8[key]!r} is not a non-negative integer")
    # The same resources in both files.
    r7 = {str(i).split("=", 1)[0]: str(i).split("=", 1)[1] for i in v7.get("default-resources", []) or []}
    for key in ("runtime", "mem_mb"):
        if str(res.get(key)) != r7.get(key):
            fail(f"profiles differ in {key}: {r7.get(key)!r} (7) against {res.get(key)!r} (8)")

    # The Snakefile's rule resources.
    with open(snakefile) as f:
        text = f.read()
    block = re.search(r"resources:\s*\n((?:\s+\w+\s*=.*\n)+)", text)
    for key in re.findall(r"^\s+(\w+)\s*=", block.group(1) if block else "", re.M):
        if key not in SLURM_PLUGIN_RESOURCES:
            fail(f"{snakefile}: resource {key!r} is not one the Slurm plugin uses")

    for p in problems:
        print("FAIL:", p)
    if not problems:
        print(f"profiles in {prof}: Snakemake 7 reads config.yaml, Snakemake >= 8 config.v8+.yaml; "
              f"{len(v8)} keys of config.v8+.yaml known to Snakemake 8 / the Slurm plugin: PASS")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
