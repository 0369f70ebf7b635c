// Output files appear whole or not at all (the quality bar: never a half-written output file).
#pragma once

#include <string>

namespace nmm {

/// What a write promises after a crash of the machine (a killed process never leaves a
/// half-written file under the final name either way: the rename is atomic).
enum class Durability {
  /// fsync of the file before the rename and of the folder after it: the file survives a power
  /// cut (mesh files, checkpoints, summaries).
  synced,
  /// the rename alone: frames and frames.pvd, rewritten many times a run, where two fsyncs per
  /// file cost more than writing the frame (docs/performance.md, "Output") and a power cut loses
  /// the run anyway. The checkpoint, written synced, is what a run restarts from.
  renamed,
};

/// Writes `contents` to `path.tmp.<pid>` in the target's folder, flushes it to disk (fsync,
/// unless Durability::renamed), renames it over `path` (atomic within one file system) and
/// flushes the folder. On failure the temporary is removed and WriteError(path, "", "cannot
/// write: <reason>") is thrown (an InputError: common/error.h). Shared by the mesh file, the checkpoint and every output writer.
void write_file_atomically(const std::string& path, const std::string& contents,
                           Durability durability = Durability::synced);

/// Makes the output folder `dir` (and its parents) and proves it writable by writing and removing
/// a probe file in it, so that a tool fails on a bad folder before its work, not after: the
/// InputError names the probe's path and why it could not be written.
void prepare_output_folder(const std::string& dir);

}  // namespace nmm
