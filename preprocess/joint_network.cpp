// Stochastic joint network generator; formulas and engine in joint_network.h, the model and the
// clipping bias in docs/joint-networks.md.
//
// Poisson (Baecher) sets: centres uniform in the region's bounding box enlarged on every side by
// a margin h = half the 0.9999 length quantile (Lmax for the power law), count
// N ~ Poisson(P21 · A_enlarged / E[L]). Joints centred outside the region but reaching into it
// are thus generated too, so the expected length inside any part of the region is P21 · A: the
// clipping (edge) bias of generating centres only inside the region, which would lose about
// P21 · perimeter · E[L²]/(4 E[L]) of length, is removed (up to the 1e-4 tail beyond h).
#include "preprocess/joint_network.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/math_constants.h"
#include "common/ring_geometry.h"

namespace nmm::pre {

namespace {

std::uint64_t splitmix64(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
Vec2 sub(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
Vec2 lerp(Vec2 a, Vec2 b, double t) { return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)}; }

/// Parameter s in [0, 1] along a–b where it crosses c–d, or -1 if it does not.
double segment_crossing(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const Vec2 r = sub(b, a), s = sub(d, c);
  const double den = cross(r, s);
  if (den == 0) return -1;
  const Vec2 ca = sub(c, a);
  const double t = cross(ca, s) / den;
  const double u = cross(ca, r) / den;
  if (t < 0 || t > 1 || u < 0 || u > 1) return -1;
  return t;
}

/// Half the length beyond which at most 1e-4 of the traces lie (Lmax for the power law).
double length_margin(const LengthDef& d) {
  switch (d.kind) {
    case LengthDistribution::constant: return 0.5 * d.mean;
    case LengthDistribution::exponential: return 0.5 * d.mean * std::log(1e4);
    case LengthDistribution::lognormal: {
      const double s2 = std::log(1 + (d.std_dev / d.mean) * (d.std_dev / d.mean));
      return 0.5 * std::exp(std::log(d.mean) - 0.5 * s2 + 3.719 * std::sqrt(s2));
    }
    case LengthDistribution::power_law: return 0.5 * d.max;
  }
  return 0;
}

/// Uniform grid over the bodies' box holding the joints of the earlier sets, so that the
/// termination search of a new trace looks only at joints in the cells its bounding box meets:
/// O(1) candidates per trace for a stationary network instead of all earlier joints (O(N·M)).
/// Cell side c = max(√(A/N), L̄/4) (A box area, N joints, L̄ their mean length), so a cell holds
/// O(1) joints and a joint meets O(1) cells; at most 2²² cells. The result (the nearest crossing
/// on each side) does not depend on the order candidates are visited in, so the grid changes no
/// output bit.
class SegmentGrid {
 public:
  SegmentGrid(const Box& box, const std::vector<JointDef>& joints, std::size_t count)
      : box_(box), stamp_(count, 0) {
    double total = 0;
    for (std::size_t k = 0; k < count; ++k)
      total += std::hypot(joints[k].points[1].x - joints[k].points[0].x,
                          joints[k].points[1].y - joints[k].points[0].y);
    const double w = std::max(box.x1 - box.x0, 1e-9), h = std::max(box.y1 - box.y0, 1e-9);
    const double n = static_cast<double>(std::max<std::size_t>(count, 1));
    double c = std::max(std::sqrt(w * h / n), 0.25 * total / n);
    c = std::max(c, std::sqrt(w * h / 4194304.0));
    nx_ = std::max(1, static_cast<int>(std::ceil(w / c)));
    ny_ = std::max(1, static_cast<int>(std::ceil(h / c)));
    cx_ = w / nx_;
    cy_ = h / ny_;
    // Counting sort into CSR arrays: cells in row-major order, joints in index order.
    std::vector<std::int32_t> count_in(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
      for (std::size_t k = 0; k < count; ++k) {
        int i0, i1, j0, j1;
        range(joints[k].points[0], joints[k].points[1], i0, i1, j0, j1);
        for (int j = j0; j <= j1; ++j)
          for (int i = i0; i <= i1; ++i) {
            const std::size_t cell = static_cast<std::size_t>(j) * nx_ + i;
            if (pass == 0) ++count_in[cell + 1];
            else items_[fill_[cell]++] = static_cast<std::int32_t>(k);
          }
      }
      if (pass == 0) {
        for (std::size_t i = 1; i < count_in.size(); ++i) count_in[i] += count_in[i - 1];
        start_ = count_in;
        fill_ = std::vector<std::int32_t>(count_in.begin(), count_in.end() - 1);
        items_.assign(static_cast<std::size_t>(count_in.back()), 0);
      }
    }
  }

  /// Calls f(k) once for every joint k whose cells meet the bounding box of a–b.
  template <class F>
  void visit(Vec2 a, Vec2 b, F&& f) {
    ++query_;
    int i0, i1, j0, j1;
    if (!range(a, b, i0, i1, j0, j1)) return;
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const std::size_t cell = static_cast<std::size_t>(j) * nx_ + i;
        for (std::int32_t m = start_[cell]; m < start_[cell + 1]; ++m) {
          const std::int32_t k = items_[m];
          if (stamp_[k] == query_) continue;
          stamp_[k] = query_;
          f(static_cast<std::size_t>(k));
        }
      }
  }

 private:
  /// Cell ranges of the bounding box of a–b, clamped to the grid; false if it misses the grid.
  bool range(Vec2 a, Vec2 b, int& i0, int& i1, int& j0, int& j1) const {
    const double x0 = std::min(a.x, b.x), x1 = std::max(a.x, b.x);
    const double y0 = std::min(a.y, b.y), y1 = std::max(a.y, b.y);
    if (x1 < box_.x0 || x0 > box_.x1 || y1 < box_.y0 || y0 > box_.y1) {
      i0 = j0 = 0;
      i1 = j1 = -1;
      return false;
    }
    auto cell = [](double v, double lo, double size, int n) {
      return std::clamp(static_cast<int>(std::floor((v - lo) / size)), 0, n - 1);
    };
    i0 = cell(x0, box_.x0, cx_, nx_);
    i1 = cell(x1, box_.x0, cx_, nx_);
    j0 = cell(y0, box_.y0, cy_, ny_);
    j1 = cell(y1, box_.y0, cy_, ny_);
    return true;
  }

  Box box_;
  int nx_ = 1, ny_ = 1;
  double cx_ = 1, cy_ = 1;
  std::vector<std::int32_t> start_, fill_, items_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t query_ = 0;
};

}  // namespace

RandomEngine::RandomEngine(std::uint64_t seed) {
  std::uint64_t x = seed;
  for (auto& s : s_) s = splitmix64(x);
}

std::uint64_t RandomEngine::next() {
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double RandomEngine::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
double RandomEngine::uniform_open() {
  return (static_cast<double>(next() >> 11) + 0.5) * 0x1.0p-53;
}

double sample_standard_normal(RandomEngine& rng) {
  const double u1 = rng.uniform_open();
  const double u2 = rng.uniform();
  return std::sqrt(-2 * std::log(u1)) * std::cos(2 * kPi * u2);
}

double sample_length(const LengthDef& d, RandomEngine& rng) {
  switch (d.kind) {
    case LengthDistribution::constant: return d.mean;
    case LengthDistribution::exponential: return -d.mean * std::log(rng.uniform_open());
    case LengthDistribution::lognormal: {
      const double s2 = std::log(1 + (d.std_dev / d.mean) * (d.std_dev / d.mean));
      return std::exp(std::log(d.mean) - 0.5 * s2 + std::sqrt(s2) * sample_standard_normal(rng));
    }
    case LengthDistribution::power_law: {
      const double e = 1 - d.exponent;
      const double lo = std::pow(d.min, e), hi = std::pow(d.max, e);
      return std::pow(lo + rng.uniform() * (hi - lo), 1 / e);
    }
  }
  return d.mean;
}

double length_cdf(const LengthDef& d, double x) {
  switch (d.kind) {
    case LengthDistribution::constant: return x < d.mean ? 0 : 1;
    case LengthDistribution::exponential: return x <= 0 ? 0 : 1 - std::exp(-x / d.mean);
    case LengthDistribution::lognormal: {
      if (x <= 0) return 0;
      const double s2 = std::log(1 + (d.std_dev / d.mean) * (d.std_dev / d.mean));
      const double mu = std::log(d.mean) - 0.5 * s2;
      return 0.5 * std::erfc(-(std::log(x) - mu) / std::sqrt(2 * s2));
    }
    case LengthDistribution::power_law: {
      if (x <= d.min) return 0;
      if (x >= d.max) return 1;
      const double e = 1 - d.exponent;
      const double lo = std::pow(d.min, e), hi = std::pow(d.max, e);
      return (std::pow(x, e) - lo) / (hi - lo);
    }
  }
  return 0;
}

double length_mean(const LengthDef& d) {
  if (d.kind != LengthDistribution::power_law) return d.mean;
  const double a = d.exponent;
  if (std::abs(a - 2) < 1e-12) return std::log(d.max / d.min) / (1 / d.min - 1 / d.max);
  return (a - 1) / (2 - a) * (std::pow(d.max, 2 - a) - std::pow(d.min, 2 - a)) /
         (std::pow(d.min, 1 - a) - std::pow(d.max, 1 - a));
}

double sample_von_mises(double kappa, RandomEngine& rng) {
  const double tau = 1 + std::sqrt(1 + 4 * kappa * kappa);
  const double rho = (tau - std::sqrt(2 * tau)) / (2 * kappa);
  const double r = (1 + rho * rho) / (2 * rho);
  for (;;) {
    const double u1 = rng.uniform(), u2 = rng.uniform_open(), u3 = rng.uniform();
    const double z = std::cos(kPi * u1);
    const double f = (1 + r * z) / (r + z);
    const double c = kappa * (r - f);
    if (c * (2 - c) - u2 > 0 || std::log(c / u2) + 1 - c >= 0) {
      const double theta = std::acos(std::clamp(f, -1.0, 1.0));
      return u3 < 0.5 ? -theta : theta;
    }
  }
}

std::int64_t sample_poisson(double lambda, RandomEngine& rng) {
  std::int64_t n = 0;
  double t = -std::log(rng.uniform_open());
  while (t <= lambda) {
    ++n;
    t -= std::log(rng.uniform_open());
  }
  return n;
}

// Sutherland–Hodgman, one box side at a time.
Ring clip_polygon_to_box(const Ring& poly, double x0, double y0, double x1, double y1) {
  Ring out = poly;
  for (int edge = 0; edge < 4; ++edge) {
    auto inside = [&](Vec2 p) {
      switch (edge) {
        case 0: return p.x >= x0;
        case 1: return p.x <= x1;
        case 2: return p.y >= y0;
        default: return p.y <= y1;
      }
    };
    auto cut = [&](Vec2 p, Vec2 q) {
      double t = 0;
      switch (edge) {
        case 0: t = (x0 - p.x) / (q.x - p.x); break;
        case 1: t = (x1 - p.x) / (q.x - p.x); break;
        case 2: t = (y0 - p.y) / (q.y - p.y); break;
        default: t = (y1 - p.y) / (q.y - p.y); break;
      }
      return lerp(p, q, t);
    };
    Ring in = out;
    out.clear();
    for (std::size_t i = 0; i < in.size(); ++i) {
      const Vec2 p = in[i], q = in[(i + 1) % in.size()];
      if (inside(q)) {
        if (!inside(p)) out.push_back(cut(p, q));
        out.push_back(q);
      } else if (inside(p)) {
        out.push_back(cut(p, q));
      }
    }
    if (out.empty()) break;
  }
  return out;
}

std::vector<std::pair<Vec2, Vec2>> clip_segment_to_polygon(Vec2 a, Vec2 b, const Ring& poly) {
  std::vector<double> ts = {0.0, 1.0};
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const double t = segment_crossing(a, b, poly[i], poly[(i + 1) % poly.size()]);
    if (t > 0 && t < 1) ts.push_back(t);
  }
  std::sort(ts.begin(), ts.end());
  std::vector<std::pair<Vec2, Vec2>> out;
  double start = -1;
  for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
    if (ts[i + 1] - ts[i] <= 0) continue;
    const bool in = point_in_ring(poly, lerp(a, b, 0.5 * (ts[i] + ts[i + 1])));
    if (in && start < 0) start = ts[i];
    if (!in && start >= 0) {
      out.emplace_back(lerp(a, b, start), lerp(a, b, ts[i]));
      start = -1;
    }
  }
  if (start >= 0) out.emplace_back(lerp(a, b, start), b);
  return out;
}

JointNetwork generate_joint_network(const std::vector<GeneratedSetInput>& sets, const Ring& box) {
  JointNetwork net;
  const Box bb = bounding_box(box);
  for (const GeneratedSetInput& in : sets) {
    const JointGenerationDef& def = in.def;
    RandomEngine rng(def.seed);
    GeneratedSetStats st;
    st.set = in.set;
    const Ring region = def.region.empty() ? box : def.region;
    st.region_area =
        std::abs(ring_signed_area(clip_polygon_to_box(region, bb.x0, bb.y0, bb.x1, bb.y1)));
    const double mean_len = length_mean(def.length);
    const double margin = length_margin(def.length);
    Box rb = bounding_box(region);
    rb = {std::max(rb.x0, bb.x0) - margin, std::max(rb.y0, bb.y0) - margin,
          std::min(rb.x1, bb.x1) + margin, std::min(rb.y1, bb.y1) + margin};
    const double theta0 = def.mean_angle_deg * kPi / 180;
    const std::size_t earlier_end = net.joints.size();  // joints of earlier sets: [0, earlier_end)
    SegmentGrid grid(bb, net.joints, earlier_end);

    auto add_trace = [&](Vec2 c, double angle, double length) {
      const Vec2 d{std::cos(angle), std::sin(angle)};
      double lo = -0.5 * length, hi = 0.5 * length;  // along d from c
      const Vec2 a{c.x + lo * d.x, c.y + lo * d.y}, b{c.x + hi * d.x, c.y + hi * d.y};
      // Termination: the first crossing with an earlier-set joint on each side of the centre.
      double plus = hi, minus = lo;
      bool hit_plus = false, hit_minus = false;
      grid.visit(a, b, [&](std::size_t k) {
        const auto& p = net.joints[k].points;
        const double s = segment_crossing(a, b, p[0], p[1]);
        if (s < 0) return;
        const double t = lo + s * (hi - lo);
        if (t >= 0 && t < plus) { plus = t; hit_plus = true; }
        if (t < 0 && t > minus) { minus = t; hit_minus = true; }
      });
      const double u_plus = rng.uniform(), u_minus = rng.uniform();  // always drawn: stable stream
      if (hit_plus) {
        ++st.sides_with_intersection;
        if (u_plus < def.termination) { ++st.sides_terminated; hi = plus; }
      }
      if (hit_minus) {
        ++st.sides_with_intersection;
        if (u_minus < def.termination) { ++st.sides_terminated; lo = minus; }
      }
      const Vec2 a2{c.x + lo * d.x, c.y + lo * d.y}, b2{c.x + hi * d.x, c.y + hi * d.y};
      for (const auto& piece : clip_segment_to_polygon(a2, b2, region)) {
        for (const auto& q : clip_segment_to_polygon(piece.first, piece.second, box)) {
          const double len = std::hypot(q.second.x - q.first.x, q.second.y - q.first.y);
          if (len <= 1e-9 * std::max(1.0, length)) continue;
          JointDef j;
          j.set = in.set;
          j.points = {q.first, q.second};
          net.joints.push_back(std::move(j));
          st.clipped_length += len;
          ++st.joints;
        }
      }
    };

    if (def.position == PositionModel::poisson) {
      st.requested_p21 = def.p21 > 0 ? def.p21 : 1 / def.mean_spacing;
      const double area = (rb.x1 - rb.x0) * (rb.y1 - rb.y0);
      const std::int64_t n = sample_poisson(st.requested_p21 * area / mean_len, rng);
      for (std::int64_t i = 0; i < n; ++i) {
        const Vec2 c{rb.x0 + rng.uniform() * (rb.x1 - rb.x0), rb.y0 + rng.uniform() * (rb.y1 - rb.y0)};
        double dev = 0;
        if (def.dispersion == DispersionKind::von_mises) dev = 0.5 * sample_von_mises(def.kappa, rng);
        if (def.dispersion == DispersionKind::uniform)
          dev = (2 * rng.uniform() - 1) * def.spread_deg * kPi / 180;
        const double len = sample_length(def.length, rng);
        st.sampled_lengths.push_back(len);
        st.angles_deg.push_back((theta0 + dev) * 180 / kPi);
        add_trace(c, theta0 + dev, len);
      }
    } else {
      // Spacing model: lines normal to n = (−sin θ̄, cos θ̄) at spacings from the spacing
      // distribution; along each line, traces and gaps alternate (a renewal process) so that the
      // covered fraction is f = P21 · s̄ (f = 1, persistent joints, when P21 is not given).
      const double s_mean = length_mean(def.spacing_distribution);
      const double f = def.p21 > 0 ? def.p21 * s_mean : 1.0;
      st.requested_p21 = f / s_mean;
      const Vec2 d{std::cos(theta0), std::sin(theta0)}, nrm{-d.y, d.x};
      Box frame = Box::empty();  // the region's box in the frame (d, nrm)
      for (const Vec2& p : box_ring(rb)) frame.add(p.x * d.x + p.y * d.y, p.x * nrm.x + p.y * nrm.y);
      const double d0 = frame.x0, d1 = frame.x1, n0 = frame.y0, n1 = frame.y1;
      const double gap_mean = mean_len * (1 / f - 1);
      double offset = n0 + rng.uniform() * sample_length(def.spacing_distribution, rng);
      while (offset <= n1) {
        st.line_offsets.push_back(offset);
        double pos = d0 - rng.uniform() * (mean_len + gap_mean);
        while (pos <= d1) {
          const double len = sample_length(def.length, rng);
          const double gap = gap_mean > 0 ? -gap_mean * std::log(rng.uniform_open()) : 0.0;
          const double mid = pos + 0.5 * len;
          st.sampled_lengths.push_back(len);
          st.angles_deg.push_back(def.mean_angle_deg);
          add_trace({mid * d.x + offset * nrm.x, mid * d.y + offset * nrm.y}, theta0, len);
          pos += len + gap;
        }
        offset += sample_length(def.spacing_distribution, rng);
      }
    }
    net.stats.push_back(std::move(st));
  }
  return net;
}

nlohmann::json explicit_scene(const nlohmann::json& doc, const SceneDef& scene,
                              JointNetwork* network) {
  std::vector<GeneratedSetInput> inputs;
  for (std::size_t i = 0; i < scene.joint_sets.size(); ++i)
    if (scene.joint_sets[i].generated)
      inputs.push_back({static_cast<int>(i), scene.joint_sets[i].generate});
  if (inputs.empty()) {
    if (network) *network = JointNetwork{};
    return doc;
  }
  const Ring box = box_ring(bodies_box(scene.bodies));
  JointNetwork net = generate_joint_network(inputs, box);
  nlohmann::json out = doc;
  nlohmann::json& joints = out["joints"];
  if (joints.is_null()) joints = nlohmann::json::array();
  for (const JointDef& j : net.joints) {
    nlohmann::json points = nlohmann::json::array();
    for (const Vec2& p : j.points) points.push_back({p.x, p.y});
    joints.push_back({{"set", scene.joint_sets[j.set].name}, {"points", points}});
  }
  // The generate block becomes generated_from: metadata the inspector compares the measured
  // network with (requested P21, region); parsers read it but never generate from it again.
  for (const GeneratedSetInput& in : inputs) {
    nlohmann::json& set = out["joint_sets"][scene.joint_sets[in.set].name];
    set["generated_from"] = set["generate"];
    set.erase("generate");
  }
  if (network) *network = std::move(net);
  return out;
}

}  // namespace nmm::pre
