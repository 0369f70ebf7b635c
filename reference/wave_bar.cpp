// A wave crossing one joint: closed form and scene (wave_bar.h has the equations).
#include "reference/wave_bar.h"

#include <algorithm>
#include <cmath>

#include "common/math_constants.h"

namespace nmm::reference {

namespace {
// The first root of f in [a, b] where f(a), f(b) differ in sign (bisection to round-off).
template <class F>
double bisect(F f, double a, double b) {
  const bool rising = f(a) < 0;
  for (int i = 0; i < 200 && b - a > 1e-15 * std::max(1.0, std::abs(b)); ++i) {
    const double m = 0.5 * (a + b);
    if ((f(m) < 0) == rising)
      a = m;
    else
      b = m;
  }
  return 0.5 * (a + b);
}
}  // namespace

JointWaveClosedForm::JointWaveClosedForm(const JointWaveSetup& s) : s_(s) {
  const double nu = s.poisson;
  m_ = s.young * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
  c_ = std::sqrt(m_ / s.density);
  z_ = s.density * c_;
  tau_ = z_ / (2 * s.kn);
  w_ = kPi / s.duration;
}

double JointWaveClosedForm::incident(double s) const {
  return (s < 0 || s > s_.duration) ? 0.0 : s_.pressure * std::sin(w_ * s);
}

double JointWaveClosedForm::transmitted(double s) const {
  if (s <= 0) return 0;
  const double a = w_ * tau_, amp = s_.pressure / (1 + a * a), T = s_.duration;
  if (s <= T) return amp * (std::sin(w_ * s) - a * std::cos(w_ * s) + a * std::exp(-s / tau_));
  return amp * a * (1 + std::exp(-T / tau_)) * std::exp(-(s - T) / tau_);
}

double JointWaveClosedForm::incident_integral(double s) const {
  if (s <= 0) return 0;
  return s_.pressure * (1 - std::cos(w_ * std::min(s, s_.duration))) / w_;
}

double JointWaveClosedForm::transmitted_integral(double s) const {
  if (s <= 0) return 0;
  const double a = w_ * tau_, amp = s_.pressure / (1 + a * a), T = s_.duration;
  const double r = std::min(s, T);
  const double upto = amp * ((1 - std::cos(w_ * r)) / w_ - tau_ * std::sin(w_ * r) +
                             a * tau_ * (1 - std::exp(-r / tau_)));
  if (s <= T) return upto;
  return upto + transmitted(T) * tau_ * (1 - std::exp(-(s - T) / tau_));
}

double JointWaveClosedForm::velocity(double x, double t) const {
  if (x > s_.joint_x) return transmitted(t - x / c_) / z_;
  const double si = t - x / c_, sr = t - (2 * s_.joint_x - x) / c_;
  return (incident(si) - (transmitted(sr) - incident(sr))) / z_;
}

double JointWaveClosedForm::displacement(double x, double t) const {
  if (x > s_.joint_x) return transmitted_integral(t - x / c_) / z_;
  const double si = t - x / c_, sr = t - (2 * s_.joint_x - x) / c_;
  return (incident_integral(si) - (transmitted_integral(sr) - incident_integral(sr))) / z_;
}

double JointWaveClosedForm::valid_until(double x) const {
  return std::min(2 * s_.joint_x + x, 2 * s_.length - x) / c_;
}

double JointWaveClosedForm::final_displacement() const { return 2 * s_.pressure / (w_ * z_); }

double JointWaveClosedForm::transmitted_peak_time() const {
  // σ_t rises while σ_i > σ_t (τσ_t' = σ_i − σ_t) and falls after: its peak is where the falling
  // half of the sine crosses it.
  return bisect([this](double s) { return incident(s) - transmitted(s); }, 0.5 * s_.duration,
                s_.duration);
}

double JointWaveClosedForm::half_rise_time(double x) const {
  const double half = 0.5 * final_displacement();
  return bisect([&](double t) { return displacement(x, t) - half; }, x / c_,
                x / c_ + s_.duration + 50 * tau_);
}

double joint_wave_kn_for_tau(const JointWaveSetup& s, double tau) {
  JointWaveSetup one = s;
  one.kn = 1;
  return JointWaveClosedForm(one).impedance() / (2 * tau);
}

SceneDef joint_wave_scene(const JointWaveSetup& w) {
  SceneDef s;
  s.name = "joint wave";
  s.plane = PlaneKind::strain;
  s.materials.push_back({"rock", w.density, w.young, w.poisson, {}});
  JointSetDef js;
  js.name = "joint";
  js.friction_deg = 45;
  js.normal.kn = w.kn;
  js.shear.ks = w.kn / 2.5;
  s.joint_sets.push_back(js);
  BodyDef bar;
  bar.material = 0;
  bar.outer = {{0, 0}, {w.length, 0}, {w.length, w.height}, {0, w.height}};
  s.bodies.push_back(bar);
  JointDef j;
  j.set = 0;
  j.points = {{w.joint_x, -0.5}, {w.joint_x, w.height + 0.5}};
  s.joints.push_back(j);
  s.mesh_size = w.h;
  // Rollers on both long faces: no strain in y, so the wave runs at the P-wave speed √(M/ρ).
  SupportDef bottom, top;
  bottom.points = {{0, 0}, {w.length, 0}};
  bottom.fix_y = true;
  top.points = {{0, w.height}, {w.length, w.height}};
  top.fix_y = true;
  s.supports = {bottom, top};
  TractionDef pulse;
  pulse.points = {{0, 0}, {0, w.height}};
  pulse.normal = -w.pressure;  // pushes into the bar
  for (int i = 0; i < w.table_rows; ++i) {
    const double f = static_cast<double>(i) / (w.table_rows - 1);
    pulse.table.time.push_back(f * w.duration);
    pulse.table.value.push_back(i == 0 || i == w.table_rows - 1 ? 0.0 : std::sin(kPi * f));
  }
  s.tractions = {pulse};
  s.measure_points = {{w.before_x, 0.5 * w.height}, {w.after_x, 0.5 * w.height}};
  const JointWaveClosedForm cf(w);
  const double t_end = std::max(cf.valid_until(w.before_x), cf.valid_until(w.after_x));
  s.solver.dynamic = true;
  s.solver.newmark_beta = 0.5;  // Shi's scheme, the one the displacement-discontinuity check is about
  s.solver.time_step = w.dt;
  s.solver.steps = static_cast<std::int64_t>(std::ceil(t_end / w.dt - 1e-9));
  s.solver.output_every = 20;  // frames; history.csv has a row per output step
  return s;
}

}  // namespace nmm::reference
