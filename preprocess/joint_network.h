// Deterministic stochastic joint network generator (issue 14; docs/joint-networks.md).
//
// Random engine (fixed here so that a seed gives the same joints on every machine):
//   SplitMix64 (Steele, Lea, Flood 2014) expands the 64-bit seed into the 256-bit state of
//   xoshiro256** (Blackman, Vigna 2018); uniform doubles u = (x >> 11) · 2⁻⁵³ in [0, 1), and
//   u' = ((x >> 11) + 0.5) · 2⁻⁵³ in (0, 1) where a logarithm is taken.
// Distributions, each by an explicit formula (no <random> distributions, whose algorithms are
// implementation-defined):
//   exponential   L = −m ln u'
//   lognormal     σ² = ln(1 + (s/m)²), μ = ln m − σ²/2, L = exp(μ + σ z),
//                 z = √(−2 ln u'₁) cos(2π u₂)  (Box–Muller, one normal per pair of draws)
//   power law     p(L) ∝ L^−a on [Lmin, Lmax]: L = (Lmin^(1−a) + u (Lmax^(1−a) − Lmin^(1−a)))^(1/(1−a))
//   von Mises     Best–Fisher (1979) rejection on the doubled angle φ = 2(θ − θ̄) (traces are
//                 axial data: θ and θ + 180° are the same joint); θ = θ̄ + φ/2
//   Poisson count N: arrivals of a unit-rate process, N = #{k : E₁ + … + E_k ≤ λ}, E = −ln u'.
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/joint_generation.h"
#include "common/scene.h"

namespace nmm::pre {

/// xoshiro256** seeded by SplitMix64.
class RandomEngine {
 public:
  explicit RandomEngine(std::uint64_t seed);
  std::uint64_t next();
  double uniform();       ///< [0, 1)
  double uniform_open();  ///< (0, 1)
 private:
  std::uint64_t s_[4];
};

double sample_length(const LengthDef& def, RandomEngine& rng);
double sample_standard_normal(RandomEngine& rng);
/// Von Mises deviate on (−π, π] with mean 0 and concentration kappa > 0 (Best–Fisher).
double sample_von_mises(double kappa, RandomEngine& rng);
std::int64_t sample_poisson(double lambda, RandomEngine& rng);
/// Cumulative distribution function of a length definition (used by the KS tests and docs).
double length_cdf(const LengthDef& def, double length);
/// Mean of a length definition, m.
double length_mean(const LengthDef& def);

struct GeneratedSetInput {
  int set = -1;  ///< index into SceneDef::joint_sets
  JointGenerationDef def;
};

struct GeneratedSetStats {
  int set = -1;
  double requested_p21 = 0;           ///< m/m²
  double region_area = 0;            ///< m², region ∩ bodies' box
  double clipped_length = 0;         ///< m, total trace length kept inside the region
  std::vector<double> sampled_lengths;  ///< m, as drawn (before termination and clipping)
  std::vector<double> angles_deg;       ///< degrees, as drawn, in (θ̄ − 90, θ̄ + 90]
  std::vector<double> line_offsets;     ///< m, spacing model: position of each line along the normal
  std::int64_t sides_with_intersection = 0;  ///< joint sides that met an earlier-set joint
  std::int64_t sides_terminated = 0;         ///< of those, sides cut there
  std::int64_t joints = 0;                   ///< joints kept (pieces inside the region)
};

struct JointNetwork {
  std::vector<JointDef> joints;  ///< two-point joints, in generation order
  std::vector<GeneratedSetStats> stats;
};

/// Generates every set in the given order (earlier sets are the ones later sets may terminate
/// at). `box` is the bodies' bounding box; each trace is clipped to the set's region (default the
/// box) and to the box.
JointNetwork generate_joint_network(const std::vector<GeneratedSetInput>& sets, const Ring& box);

/// The explicit scene of a scene document with generated joint sets: every set's `generate`
/// block is run (sets in name order, so earlier sets are those with smaller names), the joints
/// are appended to /joints as two-point joints and each `generate` block is renamed
/// `generated_from` (metadata: it generates nothing when parsed again), so that the
/// result is an ordinary scene that nmm-solve and nmm-inspect re-parse with the same geometry.
/// `scene` is the parsed `doc`; `network` (optional) receives the joints and statistics.
nlohmann::json explicit_scene(const nlohmann::json& doc, const SceneDef& scene,
                              JointNetwork* network = nullptr);

/// Clips segment a–b to a simple polygon: the pieces inside, in order along a–b.
std::vector<std::pair<Vec2, Vec2>> clip_segment_to_polygon(Vec2 a, Vec2 b, const Ring& poly);

/// Clips a polygon to the axis-aligned box [x0, x1] × [y0, y1] (Sutherland–Hodgman; exact for a
/// convex polygon, and its area is right for any simple one).
Ring clip_polygon_to_box(const Ring& poly, double x0, double y0, double x1, double y1);

}  // namespace nmm::pre
