// The step's system as a form: see form.h. The integrators here are thin objects over
// integrators.h's kernels, which hold the equations.
#include "solver/discretisation/form.h"

#include "solver/discretisation/absorbing_boundary.h"
#include "solver/discretisation/newmark.h"
#include "solver/discretisation/static_support.h"

namespace nmm::solve {

namespace {

class Elasticity final : public ElementIntegrator {
 public:
  explicit Elasticity(const Model& model) : model_(model) {}
  const char* name() const override { return "elasticity"; }
  void add(const ElementGeometry& g, std::size_t e, Mat6& k, Vec6&) override {
    integrators::elasticity(g, model_.elasticity(e), k);
  }
  void add(const ElementGeometry& g, std::size_t e, Eigen::MatrixXd& k, Eigen::VectorXd&) override {
    integrators::elasticity(g, model_.elasticity(e), k);
  }

 private:
  const Model& model_;
};

class InitialStress final : public ElementIntegrator {
 public:
  const char* name() const override { return "initial_stress"; }
  bool begin(const StepContext& step) override {
    stress_ = step.s.stress.data();
    per_element_ = 3 * static_cast<std::size_t>(step.config.space().terms());
    return true;
  }
  void add(const ElementGeometry& g, std::size_t e, Mat6&, Vec6& f) override {
    integrators::initial_stress(g, stress_ + per_element_ * e, f);
  }
  void add(const ElementGeometry& g, std::size_t e, Eigen::MatrixXd&, Eigen::VectorXd& f) override {
    integrators::initial_stress(g, stress_ + per_element_ * e, f);
  }

 private:
  const double* stress_ = nullptr;  // Pa, the state's [3·T·me] coefficients
  std::size_t per_element_ = 3;
};

class BodyForce final : public ElementIntegrator {
 public:
  explicit BodyForce(const Model& model) : model_(model) {}
  const char* name() const override { return "body_force"; }
  bool begin(const StepContext& step) override {
    bx_ = step.body_force[0];
    by_ = step.body_force[1];
    return bx_ != 0 || by_ != 0;
  }
  void add(const ElementGeometry& g, std::size_t e, Mat6&, Vec6& f) override {
    integrators::body_force(g, model_.density(e), bx_, by_, f);
  }
  void add(const ElementGeometry& g, std::size_t e, Eigen::MatrixXd&, Eigen::VectorXd& f) override {
    integrators::body_force(g, model_.density(e), bx_, by_, f);
  }

 private:
  const Model& model_;
  double bx_ = 0, by_ = 0;  // m/s², b = g − a_base(t_end)
};

class Inertia final : public ElementIntegrator {
 public:
  explicit Inertia(const Model& model) : model_(model) {}
  const char* name() const override { return "inertia"; }
  bool begin(const StepContext& step) override {
    c_ = step.inertia;
    s_ = &step.s;
    terms_ = step.config.space().terms();
    return true;
  }
  void add(const ElementGeometry& g, std::size_t e, Mat6& k, Vec6& f) override {
    integrators::inertia(g, model_.density(e), c_, covers(e), *s_, k, f);
  }
  void add(const ElementGeometry& g, std::size_t e, Eigen::MatrixXd& k, Eigen::VectorXd& f) override {
    integrators::inertia(g, model_.density(e), c_, covers(e), *s_, terms_, k, f);
  }

 private:
  const std::int32_t* covers(std::size_t e) const { return &model_.mesh().element_covers[3 * e]; }
  const Model& model_;
  InertiaCoefficients c_;
  const RunState* s_ = nullptr;  // v0, a0
  int terms_ = 1;
};

/// A boundary term of one function.
class BoundaryTerm final : public BoundaryIntegrator {
 public:
  using Term = void (*)(const Model&, const StepContext&, SystemMatrix&, Eigen::VectorXd&);
  BoundaryTerm(const char* name, Term term) : name_(name), term_(term) {}
  const char* name() const override { return name_; }
  void add(const Model& model, const StepContext& step, SystemMatrix& system,
           Eigen::VectorXd& rhs) const override {
    term_(model, step, system, rhs);
  }

 private:
  const char* name_;
  Term term_;
};

/// DDA's static inertia 2M/Δt² on the elements of free pieces only, in steps without inertia
/// (static_support.h free_pieces): from rest, so only the matrix term (v0 = a0 = 0).
class PieceInertia final : public ElementIntegrator {
 public:
  explicit PieceInertia(const Model& model) : model_(model) {}
  const char* name() const override { return "piece_inertia"; }
  bool begin(const StepContext& step) override {
    piece_ = free_pieces(model_, step.s);
    c_ = {step.inertia.on_d, 0, 0};
    s_ = &step.s;
    terms_ = step.config.space().terms();
    return !piece_.empty();
  }
  void add(const ElementGeometry& g, std::size_t e, Mat6& k, Vec6& f) override {
    if (piece_[e]) integrators::inertia(g, model_.density(e), c_, covers(e), *s_, k, f);
  }
  void add(const ElementGeometry& g, std::size_t e, Eigen::MatrixXd& k, Eigen::VectorXd& f) override {
    if (piece_[e]) integrators::inertia(g, model_.density(e), c_, covers(e), *s_, terms_, k, f);
  }

 private:
  const std::int32_t* covers(std::size_t e) const { return &model_.mesh().element_covers[3 * e]; }
  const Model& model_;
  std::vector<std::uint8_t> piece_;  // [me]
  InertiaCoefficients c_;
  const RunState* s_ = nullptr;
  int terms_ = 1;
};

}  // namespace

Form::Form(const Model& model) : model_(model) {
  const SceneDef& scene = model.scene();
  element_.push_back(std::make_unique<Elasticity>(model));
  element_.push_back(std::make_unique<InitialStress>());
  if (scene.has_gravity || !scene.base_acceleration_x.empty() || !scene.base_acceleration_y.empty())
    element_.push_back(std::make_unique<BodyForce>(model));
  if (model.step_inertia()) element_.push_back(std::make_unique<Inertia>(model));
  else if (scene.fracture.present) element_.push_back(std::make_unique<PieceInertia>(model));
  using S = const StepContext&;
  if (!model.fixed_points().empty())
    boundary_.push_back(std::make_unique<BoundaryTerm>(
        "fixed_points", [](const Model& m, S st, SystemMatrix& k, Eigen::VectorXd& f) {
          fixed_point_terms(m, st.config, st.s, k, f);
        }));
  if (!model.load_points().empty())
    boundary_.push_back(std::make_unique<BoundaryTerm>(
        "point_loads", [](const Model& m, S st, SystemMatrix&, Eigen::VectorXd& f) {
          point_load_terms(m, st.config, st.s, st.t_end, f);
        }));
  if (!model.support_edges().empty())
    boundary_.push_back(std::make_unique<BoundaryTerm>(
        "supports", [](const Model& m, S st, SystemMatrix& k, Eigen::VectorXd& f) {
          support_terms(m, st.config, st.s, st.removed, st.t_end, k, f);
        }));
  if (!model.traction_edges().empty())
    boundary_.push_back(std::make_unique<BoundaryTerm>(
        "tractions", [](const Model& m, S st, SystemMatrix&, Eigen::VectorXd& f) {
          traction_terms(m, st.config, st.s, st.removed, st.t_end, f);
        }));
  if (model.water().active())
    boundary_.push_back(std::make_unique<BoundaryTerm>(
        "water", [](const Model& m, S st, SystemMatrix&, Eigen::VectorXd& f) {
          water_terms(m, st.config, st.s, st.removed, f);
        }));
  if (!model.interface_edges().empty())
    boundary_.push_back(std::make_unique<BoundaryTerm>(
        "interface_traction", [](const Model& m, S st, SystemMatrix&, Eigen::VectorXd& f) {
          interface_traction_terms(m, st.config, st.s, st.removed, f);
        }));
  if (!scene.absorbing.empty()) boundary_.push_back(std::make_unique<BoundaryTerm>("absorbing", absorbing_terms));
}

std::vector<std::string> Form::names() const {
  std::vector<std::string> n;
  for (const auto& i : element_) n.emplace_back(i->name());
  for (const auto& i : boundary_) n.emplace_back(i->name());
  return n;
}

void Form::assemble(const StepContext& step, SystemMatrix& system, Eigen::VectorXd& rhs) {
  system.set_zero();
  rhs.setZero();
  std::vector<ElementIntegrator*> active;
  for (const auto& i : element_)
    if (i->begin(step)) active.push_back(i.get());
  const Mesh& mesh = model_.mesh();
  const CoverSpace& space = step.config.space();
  const int nd = space.element_dofs();
  Eigen::MatrixXd k(nd, nd);
  Eigen::VectorXd fe(nd);
  Mat6 k6;
  Vec6 f6;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    const int* g = space.element_unknowns(e);
    if (step.removed[e]) {  // excavated: its covers' unknowns are held at zero
      k = model_.pin_stiffness() * Eigen::MatrixXd::Identity(nd, nd);
      system.add_group(e, k.data());
      continue;
    }
    const ElementGeometry geo = element_geometry(step.config, mesh, step.s.loop_xy, e);
    if (space.order() == 0) {  // constant strain: the 6×6 fast paths
      k6.setZero();
      f6.setZero();
      for (ElementIntegrator* i : active) i->add(geo, e, k6, f6);
      system.add_group(e, k6.data());
      for (int i = 0; i < 6; ++i) rhs[g[i]] += f6[i];
      continue;
    }
    k.setZero();
    fe.setZero();
    for (ElementIntegrator* i : active) i->add(geo, e, k, fe);
    system.add_group(e, k.data());
    for (int i = 0; i < nd; ++i) rhs[g[i]] += fe[i];
  }
  for (const auto& b : boundary_) b->add(model_, step, system, rhs);
}

}  // namespace nmm::solve
