// Limits that keep a scene within what the tools can represent and finish. The physical ones
// lie orders of magnitude beyond any rock (or steel, or diamond) so that they refuse only typing
// accidents, and they bound every product the solver forms: the largest matrix entry,
// 2·ρ·A/Δt² ≤ 1e5 · 4e14 / 1e-24 = 4e43, and its square stay finite (docs/preprocess.md,
// "Limits"). The scene's readers (common/scene/) refuse a value beyond them with its JSON path.
#pragma once

namespace nmm {

constexpr double kMaxCoordinate = 1e7;         ///< m, |x| and |y| of any point
constexpr double kMaxMeshTriangles = 5e6;      ///< triangles over the bodies' bounding box
constexpr double kMaxDensity = 1e5;            ///< kg/m³ (osmium: 2.26e4)
constexpr double kMaxModulus = 1e13;           ///< Pa, Young's modulus (diamond: 1.2e12)
constexpr double kMaxStrength = 1e11;          ///< Pa, cohesion, tensile strength, JCS, UCS
constexpr double kMaxSpringStiffness = 1e17;   ///< N/m (point springs) or Pa/m (joint laws)
constexpr double kMaxClosure = 1;              ///< m, maximum joint closure Vm
constexpr double kMaxAcceleration = 1e5;       ///< m/s², each gravity component (1e4 g)
constexpr double kMaxForce = 1e15;             ///< N per unit thickness, each load component
constexpr double kMinTimeStep = 1e-12;         ///< s
constexpr double kMaxTimeStep = 1e6;           ///< s
constexpr double kMaxGeneratedJoints = 1e6;    ///< expected joints of one generated set

}  // namespace nmm
