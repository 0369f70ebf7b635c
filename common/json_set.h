// `--set PATH=VALUE` on a JSON document, shared by nmm-solve (variants on the embedded scene)
// and nmm-preprocess (e.g. joint_sets.NAME.generate.seed=K for another realisation).
// The rules (path syntax, VALUE as JSON or a bare string, null removes) are those of
// solver/run_config.cpp, rule 3, and docs/interface.md.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace nmm {

/// Applies one `--set PATH=VALUE` to `doc`; InputError("--set", text, what) on a mistake.
void apply_set(nlohmann::json& doc, const std::string& text);

}  // namespace nmm
