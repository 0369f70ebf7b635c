// `--set PATH=VALUE` on a JSON document, shared by nmm-solve (variants on the embedded scene)
// and nmm-preprocess (e.g. joint_sets.NAME.generate.seed=K for another realisation).
// The rules (path syntax, VALUE as JSON or a bare string, null removes) are those of
// common/run_config.cpp, rule 3, and docs/interface.md.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace nmm {

/// Applies one `--set PATH=VALUE` to `doc`; InputError("--set", text, what) on a mistake.
void apply_set(nlohmann::json& doc, const std::string& text);

class InputError;

/// Called when the scene `doc` (= `base` after --set) failed to parse with `error`. A --set into
/// a joint set or material that `base` lacks creates it (a new set may be built one --set at a
/// time); when that new object is incomplete the likely cause is a misspelt name, so this throws
/// InputError("--set", "/joint_sets/NAME", "no joint set 'NAME'; joint sets are: a, b (...)")
/// naming the sets `base` has. Returns when no such name was created (rethrow `error` then).
void throw_if_misspelt_name(const nlohmann::json& base, const nlohmann::json& doc,
                            const InputError& error);

}  // namespace nmm
