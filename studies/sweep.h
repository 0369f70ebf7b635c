// Parameter sweeps: a sweep file expanded into independent runs, collected into one sweep.csv.
//
// Sweep file (JSON, comments allowed; relative paths are relative to the sweep file):
//   {
//     "mesh": "tunnel.nmm",                 // base mesh, or
//     "scene": "tunnel.json",               //   a scene, preprocessed once (or per run, below)
//     "config": "base_variant.json",        // optional: nmm-solve --config for every run
//     "set": ["solver.steps=100"],          // optional: nmm-solve --set for every run
//     "variants": [                         // optional list of named variants ...
//       { "name": "bb", "set": ["joint_sets.foliation.normal.model=bandis_barton"],
//         "preprocess_set": ["joint_sets.foliation.generate.seed=3"] } ],
//     "product": {                          // ... and/or a product of --set values
//       "joint_sets.foliation.friction_deg": [25, 30, 35] },
//     "preprocess_product": {               // a product of nmm-preprocess --set values
//       "joint_sets.foliation.generate.seed": [1, 2, 3] },
//     "outputs": { "summary": ["status", "steps_completed", "simulated_time", "max_penetration"],
//                  "history": ["ux", "uy"] }  // last row of history.csv, per measure point
//   }
// The runs are the list (or one unnamed variant) × the product × the preprocess product. A run
// with any preprocess_set gets its own mesh: nmm-preprocess SCENE -o RUN/mesh.nmm --set … then
// nmm-solve; this needs a scene (not a mesh) and nmm-preprocess's --set (DFN seeds of generated
// joint sets, docs/fos-and-sweeps.md). Every run is one Job (job_runner.h), so the threads
// engine and Snakemake (local or Slurm) run the same commands.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "studies/job_runner.h"

namespace nmm::studies {

struct SweepRun {
  std::string id;                          ///< r0001, r0002, …
  std::string name;                        ///< the variant in words
  std::vector<std::pair<std::string, std::string>> values;  ///< (parameter, value) varied
  std::vector<std::string> sets;           ///< nmm-solve --set, in order
  std::vector<std::string> preprocess_sets;  ///< nmm-preprocess --set
};

struct Sweep {
  std::string mesh;    ///< absolute path or ""
  std::string scene;   ///< absolute path or ""
  std::string config;  ///< absolute path or ""
  std::vector<SweepRun> runs;
  std::vector<std::string> summary_outputs;  ///< keys of summary.json
  std::vector<std::string> history_outputs;  ///< columns of history.csv (last row per point)
  std::vector<std::string> parameters;       ///< varied parameters, in column order
};

/// Reads and expands a sweep file; InputError (file, JSON path) on bad input.
Sweep read_sweep(const std::string& path);

/// The jobs of the sweep; `base_mesh` is the mesh runs without preprocess_set use.
std::vector<Job> sweep_jobs(const Sweep& sweep, const std::string& root, const std::string& base_mesh,
                            const std::string& solve, const std::string& preprocess);

/// sweep.csv text: one row per run (variant, parameters, status, exit, wall time, outputs).
std::string sweep_csv(const Sweep& sweep, const std::string& root, const std::vector<JobResult>& results);

}  // namespace nmm::studies
