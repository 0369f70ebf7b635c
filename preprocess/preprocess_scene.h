// A scene as nmm-preprocess cuts it, in the steps the tool and the Python module (python/) share:
//
//   prepare_scene   the scene's text with --set applied (json_set.h), parsed and validated
//                   (parse_scene; a misspelt joint set or material named), generated joint sets
//                   expanded into the explicit scene the mesh embeds (joint_network.h), the
//                   geometry checked (scene_geometry.h)
//   scene_warnings  what is legal but likely a mistake (scene_checks.h), and a mesh so large
//                   that the cut takes minutes
//   cut_scene       the covers cut (cover_cutter.h) and the scene embedded in the mesh
//
// Every mistake is an InputError naming the scene and the JSON path (exit status 2 in the tools,
// nmm.SceneError in Python), with the same words wherever the scene comes from.
#pragma once

#include <string>
#include <vector>

#include "common/mesh.h"
#include "common/scene.h"
#include "preprocess/cover_cutter.h"

namespace nmm::pre {

/// Triangles from which a warning says that the cut takes minutes and the mesh file is large
/// (docs/preprocess.md, "Large meshes"; measured there).
constexpr double kLargeMeshTriangles = 5e5;

struct PreparedScene {
  SceneDef scene;    ///< parsed and checked, generated joints listed
  std::string text;  ///< the scene the mesh embeds: the file's text verbatim, or the document
                     ///< after --set or with its generated joints listed
  std::string name;  ///< names the scene in errors and warnings: the file, "FILE with --set"
  std::string file;  ///< the scene file as given (Mesh::scene_file)
};

/// The scene `text` read from `file` (a path, or any name for a scene held in memory) with
/// `sets` applied in order (PATH=VALUE, json_set.h), parsed, its generated joint sets expanded
/// and its geometry checked. Throws InputError("FILE: /json/path: what").
PreparedScene prepare_scene(std::string text, const std::string& file,
                            const std::vector<std::string>& sets);

/// Triangles of side h over the bodies' area: what the cut's time and the mesh's size follow.
double estimated_triangles(const SceneDef& scene);

/// The scene's warnings, one line each ("NAME: /json/path: warning: what"): a joint touching no
/// body (an InputError instead when `strict_joints`), a mesh size above a body's inradius, a
/// mesh of kLargeMeshTriangles triangles or more.
std::vector<std::string> scene_warnings(const PreparedScene& scene, bool strict_joints);

/// Cuts the covers of a prepared scene and embeds the scene (text, file, SHA-256) in the mesh.
/// Throws InputError naming the bodies that overlap.
Mesh cut_scene(const PreparedScene& scene, CutTimings* timings = nullptr);

}  // namespace nmm::pre
