// Definition of a generated (stochastic) joint set: what a `joint_sets.NAME.generate` block says
//. Plain data; the sampling itself lives in preprocess/joint_network.h.
//
// Model (2D traces): a set has a mean orientation θ̄ (degrees, counter-clockwise from +x, the
// trace direction; 180° periodic), a dispersion (von Mises κ on the doubled angle, or a uniform
// spread ±Δ), an intensity P21 (trace length per unit area) or a mean spacing s̄ (for parallel
// joints P21 = 1/s̄), a trace length distribution and a position model:
//  - poisson: centres uniform in the region (Baecher model), count N ~ Poisson(P21·A / E[L]);
//  - spacing: parallel joints whose centres lie on lines normal to θ̄ separated by spacings
//    drawn from the spacing distribution, centres uniform along each line.
// Termination: with probability p a new joint stops at its first intersection, on each side of
// its centre, with a joint of an earlier set (sets are generated in name order).
#pragma once

#include <cstdint>
#include <vector>

#include "common/vec2.h"

namespace nmm {

enum class LengthDistribution { constant, exponential, lognormal, power_law };

struct LengthDef {
  LengthDistribution kind = LengthDistribution::constant;
  double mean = 0;      ///< m, > 0 (constant, exponential, lognormal)
  double std_dev = 0;   ///< m, > 0 (lognormal)
  double exponent = 0;  ///< –, a > 1 in p(L) ∝ L^-a (power law)
  double min = 0;       ///< m, > 0 (power law; also a lower clip for the others if > 0)
  double max = 0;       ///< m, > min (power law)
};

enum class DispersionKind { none, von_mises, uniform };
enum class PositionModel { poisson, spacing };

struct JointGenerationDef {
  Ring region;                      ///< m, empty: the bodies' bounding box
  double mean_angle_deg = 0;        ///< degrees, trace direction counter-clockwise from +x
  DispersionKind dispersion = DispersionKind::none;
  double kappa = 0;                 ///< –, von Mises concentration (> 0) on 2θ
  double spread_deg = 0;            ///< degrees, half-width of a uniform spread, in (0, 90]
  double p21 = 0;                   ///< m/m², > 0 (or derived from spacing: 1/spacing)
  double mean_spacing = 0;          ///< m, > 0 when given instead of p21 (or for `spacing`)
  PositionModel position = PositionModel::poisson;
  LengthDef spacing_distribution;   ///< m, spacing between parallel joints (spacing model)
  LengthDef length;                 ///< m, trace length
  double termination = 0;           ///< –, in [0, 1]
  std::uint64_t seed = 1;           ///< engine seed (preprocess/joint_network.h)
};

}  // namespace nmm
