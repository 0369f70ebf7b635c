// Linear elasticity of a manifold element with constant cover functions (first-order NMM).
#pragma once

#include <Eigen/Dense>

#include "solver/discretisation/element_integration.h"
#include "common/scene.h"

namespace nmm::solve {

using Mat3 = Eigen::Matrix3d;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec3 = Eigen::Vector3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat36 = Eigen::Matrix<double, 3, 6>;

/// Elasticity matrix D (Pa) relating (σxx, σyy, τxy) to (εxx, εyy, γxy).
Mat3 elasticity_matrix(const MaterialDef& m, PlaneKind plane);

/// Strain–displacement matrix B (1/m): ε = B·d with d = (u0, v0, u1, v1, u2, v2), the
/// displacements of the element's three physical covers.
Mat36 strain_matrix(const TriangleWeights& w);

}  // namespace nmm::solve
