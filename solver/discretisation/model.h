// The model a run steps: everything derived once from the mesh and the scene and never changed
// by a step. Built by TimeStepper and shared by const reference with the contacts (ContactSet),
// the energy meter (EnergyMeter) and the output, so that each derived quantity has one home:
//
//   D_m      elasticity matrix of material m (elasticity.h; plane stress or strain), Pa
//   D_m⁻¹    its compliance (energy.h's strain energy ½ σᵀD⁻¹σ), 1/Pa
//   m(e)     the material of element e (its body's)
//   k_f      fixed-point penalty, N/m:        solver.fixed_point_stiffness, else 100·E_max·(1 m)
//   k_s      support penalty per length, N/m²: solver.support_stiffness,   else 100·E_max/h
//   k_pin    holds excavated covers at zero, N/m:  max(E_max·(1 m), 1)
//   kn_int   default interface (touching bodies without interface_set), Pa/m: 20·E_max/h,
//            ks_int = kn_int/2.5
//   w0       half the model size (DDA's w0): the scale of the displacement ratio and of the
//            contact tolerances
// plus the boundary edges under each support, traction and absorbing boundary,
// the faces between bodies (in-situ traction) and the water in the joints (joint_water.h).
//
// Why 100·E: a penalty spring stands for a rigid constraint, so it must be much stiffer than the
// material it holds (Shi's DDA recommends 10–100·E); under a reaction R a fixed point then gives
// way by R/k_f — 1 µm for 1 MN at E = 10 GPa. Stiffer springs only worsen the matrix's
// conditioning. A support spreads the same stiffness over a mesh size h of edge.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solver/discretisation/boundary_conditions.h"
#include "solver/discretisation/elasticity.h"
#include "solver/discretisation/joint_water.h"
#include "common/mesh.h"
#include "solver/discretisation/run_state.h"
#include "common/scene.h"

namespace nmm::solve {

/// Default penalty stiffnesses, each a multiple of the stiffest material's Young's modulus E_max
/// (the reasons are at the top of model.h).
struct PenaltyDefaults {
  /// –, k_f = this × E_max × (1 m): stiff against the material, not so stiff it spoils the
  /// conditioning (DDA: 10–100·E).
  static constexpr double kFixedPoint = 100.0;
  /// –, k_s = this × E_max / h: the fixed point's stiffness spread over a mesh size of edge.
  static constexpr double kSupport = 100.0;
  /// –, kn = this × E_max / h for the default interface of touching bodies: as stiff as the
  /// material over a twentieth of an element, so a contact standing for a length h of face has
  /// DDA's 20·E·(1 m) and the faces' overlap vanishes as h → 0, as rigid contact should.
  static constexpr double kInterface = 20.0;
  /// –, ks = kn / this for the default interface (a shear spring softer than the normal one,
  /// as for rock joints).
  static constexpr double kInterfaceShearRatio = 2.5;
};

class Model {
 public:
  /// Derives the model; InputError naming `scene_name` and the scene path for a mesh its scene
  /// does not describe (more bodies than the scene, a support polyline on no boundary edge, a
  /// point outside every body...).
  Model(const Mesh& mesh, const SceneDef& scene, const std::string& scene_name);

  const Mesh& mesh() const { return mesh_; }
  const SceneDef& scene() const { return scene_; }
  /// Names the scene in errors (e.g. "MESH.nmm (embedded scene)").
  const std::string& scene_name() const { return scene_name_; }

  // ---- materials -------------------------------------------------------------------------
  /// Material index of element e.
  std::int32_t material_of(std::size_t e) const { return elem_mat_[e]; }
  /// D of element e's material, Pa.
  const Mat3& elasticity(std::size_t e) const { return material_d_[elem_mat_[e]]; }
  /// D⁻¹ of element e's material, 1/Pa.
  const Mat3& compliance(std::size_t e) const { return compliance_[elem_mat_[e]]; }
  /// kg/m³, of element e's material.
  double density(std::size_t e) const { return scene_.materials[elem_mat_[e]].density; }
  /// Pa, the largest Young's modulus of the scene's materials.
  double young_max() const { return e_max_; }

  // ---- penalty springs -------------------------------------------------------------------
  double fixed_point_stiffness() const { return fixed_k_; }  ///< N/m
  double support_stiffness() const { return support_k_; }    ///< N/m² (per unit edge length)
  double pin_stiffness() const { return pin_k_; }            ///< N/m, excavated covers

  // ---- contact ---------------------------------------------------------------------------
  /// Whether two faces can ever touch: joints, or more than one block that the scene does not
  /// excavate at the start (an opening cut out of a single unjointed block leaves none).
  bool contacts_can_arise() const { return contacts_can_arise_; }

  // ---- edge sets -------------------------------------------------------------------------
  /// [support] the boundary edges under it.
  const std::vector<std::vector<BoundaryEdge>>& support_edges() const { return support_edges_; }
  /// [traction] the boundary edges under it.
  const std::vector<std::vector<BoundaryEdge>>& traction_edges() const { return traction_edges_; }
  /// [absorbing boundary] the boundary edges under it (absorbing_boundary.h).
  const std::vector<std::vector<BoundaryEdge>>& absorbing_edges() const { return absorbing_edges_; }
  /// Faces between bodies (the in-situ stress's traction while a neighbour is excavated); empty
  /// without in-situ stress.
  const std::vector<InterfaceEdge>& interface_edges() const { return interface_edges_; }
  /// Water pressure on joint faces and boundaries.
  const JointWater& water() const { return water_; }

  // ---- points ----------------------------------------------------------------------------
  /// The scene's fixed points, load points and measure points where they start: each in the
  /// element that contains it, else the nearest within 1e-6·h (a point on a boundary).
  const std::vector<TrackedPoint>& fixed_points() const { return fixed_; }
  const std::vector<TrackedPoint>& load_points() const { return loads_; }
  const std::vector<TrackedPoint>& measure_points() const { return measure_; }

  // ---- scales and the kind of step -------------------------------------------------------
  /// m, half the model size (the larger side of the mesh's bounding box, halved).
  double w0() const { return w0_; }
  /// The step's matrix has the inertia term: dynamic runs and DDA static ones.
  bool step_inertia() const {
    return scene_.solver.dynamic || scene_.solver.static_mode == StaticMode::dda;
  }

 private:
  const Mesh& mesh_;
  const SceneDef& scene_;
  std::string scene_name_;
  JointWater water_;
  std::vector<Mat3> material_d_;    // [material] elasticity matrix, Pa
  std::vector<Mat3> compliance_;    // [material] its inverse, 1/Pa
  std::vector<std::int32_t> elem_mat_;  // [me] material index
  double e_max_ = 0;                // Pa
  double fixed_k_ = 0;              // N/m
  double support_k_ = 0;            // N/m²
  double pin_k_ = 0;                // N/m
  bool contacts_can_arise_ = false;
  std::vector<std::vector<BoundaryEdge>> support_edges_;
  std::vector<std::vector<BoundaryEdge>> traction_edges_;
  std::vector<std::vector<BoundaryEdge>> absorbing_edges_;
  std::vector<InterfaceEdge> interface_edges_;
  std::vector<TrackedPoint> fixed_, loads_, measure_;
  double w0_ = 0;                   // m
};

}  // namespace nmm::solve
