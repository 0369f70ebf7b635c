// The step's system as a form (MFEM's BilinearForm and LinearForm in one): the list of the
// integrators the scene calls for, built once from the Model, each adding its term of
//     K d = F     (K: N/m, F: N; integrators.h has every term's equation)
// Assembly walks the list: per element, the element integrators add into the element's matrix
// and force (both start at zero), which go into the system's element group and the rhs; then
// the boundary integrators add theirs, in the list's order (the order fixes the round-off: a
// checkpointed run and its restart sum alike).
//
//   element    elasticity, initial stress        always
//              body force                        gravity or a base acceleration (skipped in a
//                                                step where b = g − a_base(t) is zero)
//              inertia                           dynamic runs and DDA static ones (newmark.h)
//   boundary   fixed points, point loads         where the scene has them
//              supports, tractions, water, in-situ traction of faces between bodies,
//              absorbing boundaries (dashpots in dynamic steps, their carried reaction)
//
// An excavated element adds no term: its covers' unknowns are pinned (K += k_pin I, excavation.h).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "solver/discretisation/configuration.h"
#include "solver/discretisation/integrators.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"
#include "solver/discretisation/step_context.h"
#include "solver/discretisation/system_matrix.h"

namespace nmm::solve {

/// A term integrated over each element.
class ElementIntegrator {
 public:
  virtual ~ElementIntegrator() = default;
  virtual const char* name() const = 0;
  /// Once per assembly, before the elements: the step's coefficients. False: the term vanishes
  /// in this step (the form skips it).
  virtual bool begin(const StepContext& /*step*/) { return true; }
  /// Adds element e's term: n = 0 the 6×6 fast path, n ≥ 1 the polynomial one.
  virtual void add(const ElementGeometry& g, std::size_t e, Mat6& k, Vec6& f) = 0;
  virtual void add(const ElementGeometry& g, std::size_t e, Eigen::MatrixXd& k, Eigen::VectorXd& f) = 0;
};

/// A term of points or edges, into the system and the rhs directly.
class BoundaryIntegrator {
 public:
  virtual ~BoundaryIntegrator() = default;
  virtual const char* name() const = 0;
  virtual void add(const Model& model, const StepContext& step, SystemMatrix& system,
                   Eigen::VectorXd& rhs) const = 0;
};

class Form {
 public:
  /// The integrators `model`'s scene calls for (it must outlive the form).
  explicit Form(const Model& model);

  /// Zeroes the system and rhs and adds every term of the step.
  void assemble(const StepContext& step, SystemMatrix& system, Eigen::VectorXd& rhs);

  /// The integrators' names, element ones first, in the order they are walked.
  std::vector<std::string> names() const;

 private:
  const Model& model_;
  std::vector<std::unique_ptr<ElementIntegrator>> element_;
  std::vector<std::unique_ptr<BoundaryIntegrator>> boundary_;
};

}  // namespace nmm::solve
