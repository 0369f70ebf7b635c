// The model derived once from the mesh and the scene: see model.h for what and why.
#include "solver/discretisation/model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.h"
#include "solver/discretisation/point_location.h"

namespace nmm::solve {

Model::Model(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name)
    : mesh_(mesh), scene_(scene), scene_name_(scene_name), water_(mesh, scene) {
  // The mesh file's dofs_per_cover describes the mesh as cut (constant covers, 2); the order of
  // the cover functions is the run's choice (solver.cover_order, docs/higher-order-covers.md).
  if (mesh.dofs_per_cover != 2)
    throw InputError(scene_name, "", "the mesh file says " + std::to_string(mesh.dofs_per_cover) +
                                         " unknowns per physical cover; meshes hold 2 (the cover "
                                         "order is chosen per run: solver.cover_order)");
  for (const MaterialDef& m : scene.materials) {
    material_d_.push_back(elasticity_matrix(m, scene.plane));
    compliance_.push_back(material_d_.back().inverse());
    e_max_ = std::max(e_max_, m.young);
  }
  fixed_k_ = scene.solver.fixed_point_stiffness > 0 ? scene.solver.fixed_point_stiffness
                                                    : PenaltyDefaults::kFixedPoint * e_max_;
  support_k_ = scene.solver.support_stiffness > 0
                   ? scene.solver.support_stiffness
                   : PenaltyDefaults::kSupport * e_max_ / mesh.mesh_size;
  // Stiff enough to hold an excavated cover still against anything its (inactive) neighbours
  // leave on it, 1 N/m at least for a scene of zero stiffness.
  pin_k_ = std::max(e_max_, 1.0);

  const std::size_t ne = mesh.element_count();
  elem_mat_.resize(ne);
  for (std::size_t e = 0; e < ne; ++e) {
    const std::int32_t body = mesh.element_body[e];
    if (body < 0 || static_cast<std::size_t>(body) >= scene.bodies.size())
      throw InputError(scene_name, "/bodies", "the mesh has more bodies than its scene");
    elem_mat_[e] = scene.bodies[body].material;
  }

  std::size_t kept = 0;
  for (std::size_t b = 0; b < mesh.block_count(); ++b)
    if (std::find(scene.excavate.begin(), scene.excavate.end(), mesh.block_body[b]) == scene.excavate.end())
      ++kept;
  contacts_can_arise_ = !scene.joints.empty() || kept > 1;

  if (scene.insitu_stress.present) interface_edges_ = solve::interface_edges(mesh, scene);
  for (std::size_t i = 0; i < scene.supports.size(); ++i)
    support_edges_.push_back(edges_under(mesh, scene.supports[i].points, scene_name,
                                         "/supports/" + std::to_string(i) + "/points"));
  for (std::size_t i = 0; i < scene.tractions.size(); ++i)
    traction_edges_.push_back(edges_under(mesh, scene.tractions[i].points, scene_name,
                                          "/tractions/" + std::to_string(i) + "/points"));
  for (std::size_t i = 0; i < scene.absorbing.size(); ++i)
    absorbing_edges_.push_back(edges_under(mesh, scene.absorbing[i].points, scene_name,
                                           "/absorbing/" + std::to_string(i) + "/points"));

  // Points: the element that contains each one, else the nearest within 1e-6·h (a point on a
  // boundary), else bad input.
  auto locate = [&](const Vec2& p, const std::string& path) {
    const PointLocation at = locate_point(mesh, mesh.loop_xy, p);
    if (at.element < 0 || at.distance > 1e-6 * mesh.mesh_size) {
      std::ostringstream os;
      os << "point (" << p.x << ", " << p.y << ") lies outside every body";
      throw InputError(scene_name, path, os.str());
    }
    return TrackedPoint{at.element, p.x, p.y, p.x, p.y};
  };
  for (std::size_t i = 0; i < scene.fixed_points.size(); ++i)
    fixed_.push_back(locate(scene.fixed_points[i], "/fixed_points/" + std::to_string(i)));
  for (std::size_t i = 0; i < scene.loads.size(); ++i)
    loads_.push_back(locate(scene.loads[i].point, "/loads/" + std::to_string(i) + "/point"));
  for (std::size_t i = 0; i < scene.measure_points.size(); ++i)
    measure_.push_back(locate(scene.measure_points[i], "/measure_points/" + std::to_string(i)));

  w0_ = 0.5 * bounding_box_xy(mesh.loop_xy).longer_side();
}

}  // namespace nmm::solve
