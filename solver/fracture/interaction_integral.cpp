// Stress intensity factors by the interaction integral, domain form (interaction_integral.h).
//
// In the tip's frame (x1 ahead along the crack, x2 to its left), for the run's field (σ, u) and
// an auxiliary field (σᵃ, uᵃ, εᵃ) of a unit K in mode I or II (Yau, Wang & Corten 1980; the
// domain form of Moës, Dolbow & Belytschko 1999, eq. 36–39):
//
//     I = ∫_A [ σ_ij ∂uᵃ_i/∂x1 + σᵃ_ij ∂u_i/∂x1 − σ_ik εᵃ_ik δ_1j ] ∂q/∂x_j dA
//     K_I = E'/2 · I(mode I),   K_II = E'/2 · I(mode II)
//
// and, where the crack's faces carry a traction t (a closed crack's contacts; the fluid in an
// open one, t = −p·n with p the flow network's pressure, linear along each face edge), minus
//     ∫_faces t_i ∂uᵃ_i/∂x1 q ds
// (the auxiliary field's faces are free; on each face edge by Gauss in s, u = s² from the end
// nearer the tip, which takes the r^−½ out), since I = 2(K_I·K_Iᵃ + K_II·K_IIᵃ)/E', E' = E/(1 − ν²) in plane strain and E in plane stress.
// Faces that do not lie on the line behind the tip (a kink of the tip's own crack inside the
// ring: a wing's flaw, a turn of a growing path) add the rest of the face integrand, for every
// face whether it carries traction or not,
//     + ∫_faces (σ_ik εᵃ_ik m_1 − σᵃ_ij m_j ∂u_i/∂x1) q ds      (m the face's outward normal),
// which vanishes on faces along the line (m_1 = 0 and σᵃ·m = 0 at θ = ±π); and the auxiliary
// fields take their cut along the crack (TipDomain::behind), not along the line behind the tip:
// at a distance r beyond the kink, θ runs on continuously from the side of the crack a point is
// on (θ ∈ (θ_c, θ_c + 2π) or (θ_c − 2π, θ_c) about the crack's angle θ_c at that r), so the
// auxiliary fields stay smooth in the rock and jump only across faces (Williams' fields hold for
// any θ). Without it the cut ran through intact rock beyond the kink and a wing's tip read
// K_I < 0 where its faces were open (docs/crack-tips.md "Wings from a closed flaw").
// q is the linear interpolation, over each element's mathematical triangle, of q = 1 at the
// mesh nodes within the domain's radius of the tip and 0 at the others, so ∂q/∂x is constant in
// an element and nonzero only in the ring of triangles with nodes on both sides of the radius:
// the tip's own element, where the field is least accurate, has q = 1 and adds nothing. The
// integral holds for no body force and no initial stress inside the ring (each would add a term;
// docs/fracture.md says which runs that leaves out). A loaded face's traction is its element's
// σ·n: at cover order 0 the stress of the element beside a closed contact, the contact's
// traction where the element is small against the field's variation.
//
// Williams' leading terms (Anderson, Fracture Mechanics, 3rd ed., table 2.2), with r, θ about
// the tip, μ the shear modulus and κ = 3 − 4ν (plane strain) or (3 − ν)/(1 + ν) (plane stress),
// s = sin(θ/2), c = cos(θ/2):
//     mode I:  u1 = √(r/2π)/(2μ) · c(κ − 1 + 2s²),   u2 = √(r/2π)/(2μ) · s(κ + 1 − 2c²)
//     mode II: u1 = √(r/2π)/(2μ) · s(κ + 1 + 2c²),   u2 = −√(r/2π)/(2μ) · c(κ − 1 − 2s²)
// Writing u = √(r/2π)/(2μ) · g(θ), the gradient is
//     ∂u/∂x1 = (g/2·cosθ − g'·sinθ) / (2μ√(2πr)),   ∂u/∂x2 = (g/2·sinθ + g'·cosθ) / (2μ√(2πr)),
// and the auxiliary stress is D·εᵃ (plane strain or stress as κ), which equals the closed-form
// σᵃ (tests/test_crack_tips.cpp checks it) and keeps σᵃ:ε = σ:εᵃ exact.
//
// Each element's integral is a sum over the triangles of a fan of its loop (signed areas: the
// slits of a joint ending in an element add nothing), each by Dunavant's 7-point rule of degree 5.
// The field is the element's stress and the displacement gradient fitted to its loop vertices'
// displacements (least squares; exact at cover order 0, where u is affine in an element; at
// orders 1 and 2 the element's mean gradient).
#include "solver/fracture/interaction_integral.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "common/math_constants.h"

namespace nmm::solve {

TipElasticity tip_elasticity(const MaterialDef& m, PlaneKind plane) {
  TipElasticity el;
  el.young = m.young;
  el.poisson = m.poisson;
  el.plane_strain = plane == PlaneKind::strain;
  el.shear_modulus = m.young / (2 * (1 + m.poisson));
  el.kolosov = el.plane_strain ? 3 - 4 * m.poisson : (3 - m.poisson) / (1 + m.poisson);
  el.e_prime = el.plane_strain ? m.young / (1 - m.poisson * m.poisson) : m.young;
  return el;
}

namespace {

// σ = D·ε (engineering shear γ = 2ε12), plane strain or stress.
std::array<double, 3> hooke(const TipElasticity& el, double e11, double e22, double e12) {
  const double E = el.young, nu = el.poisson;
  const double G = E / (2 * (1 + nu));
  if (el.plane_strain) {
    const double f = E / ((1 + nu) * (1 - 2 * nu));
    return {f * ((1 - nu) * e11 + nu * e22), f * (nu * e11 + (1 - nu) * e22), 2 * G * e12};
  }
  const double f = E / (1 - nu * nu);
  return {f * (e11 + nu * e22), f * (nu * e11 + e22), 2 * G * e12};
}

// Dunavant's degree-5 rule on a triangle: barycentric points and weights (summing to 1).
constexpr double kA = 0.059715871789770, kB = 0.470142064105115, kWab = 0.132394152788506;
constexpr double kC = 0.797426985353087, kD = 0.101286507323456, kWcd = 0.125939180544827;
constexpr double kRule[7][4] = {{1.0 / 3, 1.0 / 3, 1.0 / 3, 0.225},
                                {kA, kB, kB, kWab}, {kB, kA, kB, kWab}, {kB, kB, kA, kWab},
                                {kC, kD, kD, kWcd}, {kD, kC, kD, kWcd}, {kD, kD, kC, kWcd}};

}  // namespace

TipField williams_field(const TipElasticity& el, int mode, double r, double theta) {
  const double s = std::sin(theta / 2), c = std::cos(theta / 2), k = el.kolosov;
  double g[2], dg[2];  // g_i(θ) and g_i'(θ)
  if (mode == 1) {
    g[0] = c * (k - 1 + 2 * s * s);
    g[1] = s * (k + 1 - 2 * c * c);
    dg[0] = -0.5 * s * (k - 1 + 2 * s * s) + 2 * s * c * c;
    dg[1] = 0.5 * c * (k + 1 - 2 * c * c) + 2 * c * s * s;
  } else {
    g[0] = s * (k + 1 + 2 * c * c);
    g[1] = -c * (k - 1 - 2 * s * s);
    dg[0] = 0.5 * c * (k + 1 + 2 * c * c) - 2 * c * s * s;
    dg[1] = 0.5 * s * (k - 1 - 2 * s * s) + 2 * s * c * c;
  }
  const double mu = el.shear_modulus;
  const double amp_u = std::sqrt(r / (2 * kPi)) / (2 * mu);
  const double amp_g = 1 / (2 * mu * std::sqrt(2 * kPi * r));
  const double ct = std::cos(theta), st = std::sin(theta);
  TipField f;
  for (int i = 0; i < 2; ++i) {
    f.u[i] = amp_u * g[i];
    f.grad[i][0] = amp_g * (0.5 * g[i] * ct - dg[i] * st);
    f.grad[i][1] = amp_g * (0.5 * g[i] * st + dg[i] * ct);
  }
  f.stress = hooke(el, f.grad[0][0], f.grad[1][1], 0.5 * (f.grad[0][1] + f.grad[1][0]));
  return f;
}

namespace {

// θ of the auxiliary fields at (x1, x2) of the tip's frame, with their cut along the crack behind
// the tip (`behind`, in the tip's frame, the tip first): the crack's angle θ_c at the point's
// distance r (where the crack first reaches r); where the crack there is within 0.6° of the line
// behind the tip, atan2's own cut (θ = ±π) is the crack's.
class AuxiliaryBranch {
 public:
  explicit AuxiliaryBranch(std::vector<std::array<double, 2>> behind) : behind_(std::move(behind)) {}
  double theta(double x1, double x2) const {
    const double theta = std::atan2(x2, x1);
    if (behind_.size() < 2) return theta;
    const double r = std::sqrt(x1 * x1 + x2 * x2), tc = crack_angle(r);
    if (std::abs(tc) >= kPi - 1e-2) return theta;
    if (tc >= 0 && theta > tc) return theta - 2 * kPi;
    if (tc < 0 && theta < tc) return theta + 2 * kPi;
    return theta;
  }

 private:
  double crack_angle(double r) const {
    for (std::size_t k = 0; k + 1 < behind_.size(); ++k) {
      const auto& p = behind_[k];
      const auto& q = behind_[k + 1];
      if (q[0] * q[0] + q[1] * q[1] < r * r) continue;
      // |p + t(q − p)| = r, the root where the crack passes outwards through r.
      const double dx = q[0] - p[0], dy = q[1] - p[1];
      const double a = dx * dx + dy * dy, b = 2 * (p[0] * dx + p[1] * dy), c = p[0] * p[0] + p[1] * p[1] - r * r;
      const double t = a > 0 ? std::clamp((-b + std::sqrt(std::max(b * b - 4 * a * c, 0.0))) / (2 * a), 0.0, 1.0) : 0.0;
      return std::atan2(p[1] + t * dy, p[0] + t * dx);
    }
    const auto& last = behind_.back();  // the crack ends within r: its cut goes on outwards
    return std::atan2(last[1], last[0]);
  }
  std::vector<std::array<double, 2>> behind_;
};

}  // namespace

StressIntensity interaction_integral(const Mesh& mesh, const TipDomain& domain, const TipElasticity& el,
                                     const std::vector<double>& stress, const std::vector<double>& loop_u,
                                     const std::vector<std::uint8_t>& skip,
                                     const std::vector<std::int32_t>* near,
                                     const std::vector<std::uint8_t>* loaded,
                                     const std::vector<double>* face_pressure) {
  const double e1x = domain.direction.x, e1y = domain.direction.y;  // the tip's frame: rows e1, e2
  const double e2x = -e1y, e2y = e1x;
  const double r2 = domain.radius * domain.radius;
  std::vector<std::array<double, 2>> behind;
  if (domain.behind != nullptr)
    for (const Vec2& p : *domain.behind) {
      const double px = p.x - domain.tip.x, py = p.y - domain.tip.y;
      behind.push_back({e1x * px + e1y * py, e2x * px + e2y * py});
    }
  const AuxiliaryBranch branch(std::move(behind));
  const double R[2][2] = {{e1x, e1y}, {e2x, e2y}};  // global → the tip's frame
  double integral[2] = {0, 0};
  StressIntensity out;
  double nearest = std::numeric_limits<double>::infinity();  // m, loop vertex to the tip
  const std::size_t count = near ? near->size() : mesh.element_count();
  for (std::size_t n = 0; n < count; ++n) {
    const std::size_t e = near ? static_cast<std::size_t>((*near)[n]) : n;
    if (mesh.element_body[e] != domain.body || (!skip.empty() && skip[e])) continue;
    // q at the triangle's nodes and its (constant) gradient.
    const std::int32_t* tn = &mesh.triangle_nodes[3 * static_cast<std::size_t>(mesh.element_triangle[e])];
    double nx[3], ny[3], q[3];
    int inside = 0;
    for (int k = 0; k < 3; ++k) {
      nx[k] = mesh.node_xy[2 * static_cast<std::size_t>(tn[k])];
      ny[k] = mesh.node_xy[2 * static_cast<std::size_t>(tn[k]) + 1];
      const double dx = nx[k] - domain.tip.x, dy = ny[k] - domain.tip.y;
      q[k] = dx * dx + dy * dy < r2 ? 1 : 0;
      inside += static_cast<int>(q[k]);
    }
    if (inside == 3)  // the tip's own elements are here: where is the tip now?
      for (std::int32_t v = mesh.element_loop_offset[e]; v < mesh.element_loop_offset[e + 1]; ++v) {
        const double d = length(mesh.loop_xy[2 * v] - domain.tip.x, mesh.loop_xy[2 * v + 1] - domain.tip.y);
        if (d < nearest) nearest = d, out.tip_u = {loop_u[2 * v], loop_u[2 * v + 1]};
      }
    if (inside == 0) continue;
    const double two_area = (nx[1] - nx[0]) * (ny[2] - ny[0]) - (nx[2] - nx[0]) * (ny[1] - ny[0]);
    // The element's displacement gradient: least squares of u = u0 + G(X − Xc) over its loop;
    // with its stress, into the tip's frame: σ' = RσRᵀ, ∇u' = R∇uRᵀ.
    const std::int32_t v0 = mesh.element_loop_offset[e], v1 = mesh.element_loop_offset[e + 1];
    const std::size_t nv = static_cast<std::size_t>(v1 - v0);
    double sl[2][2] = {}, gl[2][2] = {};
    bool gradient = false;
    if (nv >= 3) {
      double cx = 0, cy = 0, ux = 0, uy = 0;
      for (std::int32_t v = v0; v < v1; ++v) {
        cx += mesh.loop_xy[2 * v], cy += mesh.loop_xy[2 * v + 1];
        ux += loop_u[2 * v], uy += loop_u[2 * v + 1];
      }
      cx /= static_cast<double>(nv), cy /= static_cast<double>(nv);
      ux /= static_cast<double>(nv), uy /= static_cast<double>(nv);
      double sxx = 0, sxy = 0, syy = 0, bx[2] = {0, 0}, by[2] = {0, 0};
      for (std::int32_t v = v0; v < v1; ++v) {
        const double dx = mesh.loop_xy[2 * v] - cx, dy = mesh.loop_xy[2 * v + 1] - cy;
        const double du[2] = {loop_u[2 * v] - ux, loop_u[2 * v + 1] - uy};
        sxx += dx * dx, sxy += dx * dy, syy += dy * dy;
        for (int i = 0; i < 2; ++i) bx[i] += dx * du[i], by[i] += dy * du[i];
      }
      const double det = sxx * syy - sxy * sxy;
      gradient = det > 1e-24 * (sxx + syy) * (sxx + syy);  // not a loop of no area
      if (gradient) {
        double grad[2][2];  // global ∂u_i/∂x_j
        for (int i = 0; i < 2; ++i) {
          grad[i][0] = (syy * bx[i] - sxy * by[i]) / det;
          grad[i][1] = (sxx * by[i] - sxy * bx[i]) / det;
        }
        const double sg[2][2] = {{stress[3 * e], stress[3 * e + 2]}, {stress[3 * e + 2], stress[3 * e + 1]}};
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 2; ++j)
            for (int a = 0; a < 2; ++a)
              for (int b = 0; b < 2; ++b) {
                sl[i][j] += R[i][a] * sg[a][b] * R[j][b];
                gl[i][j] += R[i][a] * grad[a][b] * R[j][b];
              }
      }
    }
    {
      // The faces: −∫ t_i ∂uᵃ_i/∂x1 q ds over this element's loaded joint edges, with t = σ_e·n
      // (n the loop's outward normal), and on every joint edge off the line behind the tip
      // + ∫ (σ:εᵃ n_1 − σᵃ_ij n_j ∂u_i/∂x1) q ds; q interpolated over the triangle; each edge in
      // four pieces of 4-point Gauss (an edge ending at the tip has an integrable r^−½).
      static constexpr double kGx[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
      static constexpr double kGw[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
      const std::int32_t f0 = v0, f1 = v1;
      for (std::int32_t v = f0; v < f1; ++v) {
        if (!(mesh.loop_edge_origin[v] & kEdgeJoint)) continue;
        const auto vi = static_cast<std::size_t>(v);
        const bool closed = loaded != nullptr && (*loaded)[vi];
        // A fluid in an open crack: t = −p·n, p linear along the edge (a closed one's σ·n holds it).
        const double pa = !closed && face_pressure != nullptr ? (*face_pressure)[2 * vi] : 0.0;
        const double pb = !closed && face_pressure != nullptr ? (*face_pressure)[2 * vi + 1] : 0.0;
        const bool traction = closed || pa != 0 || pb != 0;
        const std::int32_t w = v + 1 < f1 ? v + 1 : f0;
        const double ax = mesh.loop_xy[2 * v], ay = mesh.loop_xy[2 * v + 1];
        const double dx = mesh.loop_xy[2 * w] - ax, dy = mesh.loop_xy[2 * w + 1] - ay, len = length(dx, dy);
        if (len == 0) continue;
        const double nxo = dy / len, nyo = -dx / len;  // outward: the loop runs counter-clockwise
        const double m1 = e1x * nxo + e1y * nyo, m2 = e2x * nxo + e2y * nyo;  // in the tip's frame
        // Along the line behind the tip the rest of the integrand is nought: only a loaded face adds.
        const bool along = std::abs(m1) < 1e-2;
        if (!traction && (along || !gradient)) continue;
        const double sx = stress[3 * e] * nxo + stress[3 * e + 2] * nyo, sy = stress[3 * e + 2] * nxo + stress[3 * e + 1] * nyo;
        // u = s² from the end nearer the tip (du = 2s·ds): the r^−½ of ∂uᵃ/∂x1 at a tip on that
        // end becomes smooth in s. (Gauss in u left 0.9 % of K_I out at h = a/10 for a
        // pressurised crack: docs/flow.md.)
        const bool from_a = length(ax - domain.tip.x, ay - domain.tip.y) <=
                            length(mesh.loop_xy[2 * w] - domain.tip.x, mesh.loop_xy[2 * w + 1] - domain.tip.y);
        for (int piece = 0; piece < 4; ++piece)
          for (int g = 0; g < 4; ++g) {
            const double sg = (piece + 0.5 + 0.5 * kGx[g]) / 4, jac = 2 * sg;
            const double u = from_a ? sg * sg : 1 - sg * sg;
            const double pu = (1 - u) * pa + u * pb;
            const double tx = closed ? sx : -pu * nxo, ty = closed ? sy : -pu * nyo;
            const double t1 = e1x * tx + e1y * ty, t2 = e2x * tx + e2y * ty;
            // A hair inside the element, so that θ is that of its own face (±π).
            const double x = ax + u * dx - 1e-9 * len * nxo, y = ay + u * dy - 1e-9 * len * nyo;
            double qx = 0;
            for (int k = 0; k < 3; ++k) {
              const int i1 = (k + 1) % 3, i2 = (k + 2) % 3;
              qx += q[k] * (nx[i1] * ny[i2] - nx[i2] * ny[i1] + (ny[i1] - ny[i2]) * x + (nx[i2] - nx[i1]) * y) / two_area;
            }
            const double px = x - domain.tip.x, py = y - domain.tip.y;
            const double x1 = e1x * px + e1y * py, x2 = e2x * px + e2y * py;
            const double r = std::sqrt(x1 * x1 + x2 * x2);
            double theta = branch.theta(x1, x2);
            // A face behind the tip within 0.6° of its line is on the crack's face of its element's
            // side (θ = ±π by the side the element lies on, −n), whatever its position says: a tip
            // that grew with a kink of 1e-6 rad leaves the faces behind it 1e-7 m to one side of
            // its line, far more than the hair, and both faces then read the same θ and cancel.
            const bool on_line = x1 < 0 && std::abs(x2) < 1e-2 * r;
            if (on_line) theta = e2x * nxo + e2y * nyo < 0 ? kPi : -kPi;
            const double weight = 0.125 * kGw[g] * jac * len * qx;
            for (int mode = 1; mode <= 2; ++mode) {
              const TipField a = williams_field(el, mode, r, theta);
              if (traction) integral[mode - 1] -= 0.125 * kGw[g] * jac * len * (t1 * a.grad[0][0] + t2 * a.grad[1][0]) * qx;
              // A sliver of a face at the tip itself (a crack end cut a round-off past an edge)
              // holds no length the field resolves.
              if (along || !gradient || !(r > 1e-6 * domain.radius)) continue;
              const double ea12 = 0.5 * (a.grad[0][1] + a.grad[1][0]);
              const double w_int = sl[0][0] * a.grad[0][0] + 2 * sl[0][1] * ea12 + sl[1][1] * a.grad[1][1];
              const double ta1 = a.stress[0] * m1 + a.stress[2] * m2, ta2 = a.stress[2] * m1 + a.stress[1] * m2;
              integral[mode - 1] += weight * (w_int * m1 - (ta1 * gl[0][0] + ta2 * gl[1][0]));
            }
          }
      }
    }
    if (inside == 3) continue;
    if (!gradient) continue;
    double qx = 0, qy = 0;
    for (int k = 0; k < 3; ++k) {
      const int a = (k + 1) % 3, b = (k + 2) % 3;
      qx += q[k] * (ny[a] - ny[b]) / two_area;
      qy += q[k] * (nx[b] - nx[a]) / two_area;
    }
    const double ql[2] = {R[0][0] * qx + R[0][1] * qy, R[1][0] * qx + R[1][1] * qy};
    // The fan of the loop from its first vertex, each triangle by the 7-point rule.
    const double px0 = mesh.loop_xy[2 * v0], py0 = mesh.loop_xy[2 * v0 + 1];
    for (std::int32_t v = v0 + 1; v + 1 < v1; ++v) {
      const double ax = mesh.loop_xy[2 * v], ay = mesh.loop_xy[2 * v + 1];
      const double bx2 = mesh.loop_xy[2 * v + 2], by2 = mesh.loop_xy[2 * v + 3];
      const double area = 0.5 * ((ax - px0) * (by2 - py0) - (bx2 - px0) * (ay - py0));
      if (area == 0) continue;
      for (const auto& p : kRule) {
        const double x = p[0] * px0 + p[1] * ax + p[2] * bx2 - domain.tip.x;
        const double y = p[0] * py0 + p[1] * ay + p[2] * by2 - domain.tip.y;
        const double x1 = e1x * x + e1y * y, x2 = e2x * x + e2y * y;
        const double r = std::sqrt(x1 * x1 + x2 * x2), theta = branch.theta(x1, x2);
        for (int mode = 1; mode <= 2; ++mode) {
          const TipField a = williams_field(el, mode, r, theta);
          const double sa[2][2] = {{a.stress[0], a.stress[2]}, {a.stress[2], a.stress[1]}};
          const double ea[2][2] = {{a.grad[0][0], 0.5 * (a.grad[0][1] + a.grad[1][0])},
                                   {0.5 * (a.grad[0][1] + a.grad[1][0]), a.grad[1][1]}};
          double w = 0;  // σ:εᵃ
          for (int i = 0; i < 2; ++i)
            for (int k = 0; k < 2; ++k) w += sl[i][k] * ea[i][k];
          double f = -w * ql[0];
          for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j) f += (sl[i][j] * a.grad[i][0] + sa[i][j] * gl[i][0]) * ql[j];
          integral[mode - 1] += p[3] * area * f;
        }
      }
    }
    ++out.elements;
  }
  out.k1 = 0.5 * el.e_prime * integral[0];
  out.k2 = 0.5 * el.e_prime * integral[1];
  return out;
}

double mts_angle(double k1, double k2) {
  if (k2 == 0) return 0;
  return 2 * std::atan((k1 - std::sqrt(k1 * k1 + 8 * k2 * k2)) / (4 * k2));
}

}  // namespace nmm::solve
