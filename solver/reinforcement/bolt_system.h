// The bolts in the step's system (docs/reinforcement.md; equations at the top of
// bolt_system.cpp): their own unknowns (a grouted cable's slips), their coupling groups in the
// sparse pattern, and each step's rows, springs and modes — linearised at the step's start and
// again at each solution of the step (Newton on a bolt's exact length), assembled into the matrix
// (material and geometric stiffness) and right-hand side, judged at the step's solution (a spring
// that yields or slips, an anchored bolt that breaks, a length the linearisation missed: the step
// is solved again), and committed into the bolts' state (run_state.h BoltState) once the step is
// accepted, never on an iterate.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "solver/discretisation/configuration.h"
#include "solver/discretisation/model.h"
#include "solver/discretisation/run_state.h"
#include "solver/discretisation/system_matrix.h"

namespace nmm::solve {

/// One spring of a bolt in a step: an anchored bolt's axial spring, a cable segment's, or the
/// grout at a cable point. The grout's force is f = f0 + k·cᵀd while elastic (c: its row, on
/// `size` unknowns from `row` in the rows' storage); an axial spring's is f = f0 + k·(ℓ(d) − ℓs),
/// ℓ(d) = √((ℓs + cᵀd)² + (c⊥ᵀd)²) its exact length at the step's end (c⊥: its row across).
struct BoltSpring {
  enum Kind : int { anchor, segment, grout };
  Kind kind = anchor;
  int bolt = 0;              ///< the scene's bolt
  int index = 0;             ///< its segment (anchor, segment) or point (grout)
  int group = -1;            ///< its coupling group among the bolts' (−1: grout, a diagonal entry)
  std::size_t row = 0;       ///< first entry of its row in the rows' storage
  int size = 0;              ///< entries of its row
  double k = 0;              ///< N/m per bolt, elastic stiffness
  double cap = 0;            ///< N per bolt, |force| limit (infinity: none)
  bool breaks = false;       ///< at the cap it breaks (anchored) instead of yielding or slipping
  double f0 = 0;             ///< N per bolt, force at the step's start
  double per_m = 1;          ///< 1/m, 1/spacing: what one bolt is per metre of the model
  double length = 0;         ///< m, ℓs: its length at the step's start (anchor, segment)
  double xk = 0, yk = 0;     ///< m, where the step is linearised: cᵀd_k, c⊥ᵀd_k (0 at the start)
  int mode = 0;              ///< 0 elastic, ±1 at the cap in tension / compression (or slip sign)
  bool broken = false;       ///< broken in this attempt (anchored)
};

/// J/m, the elastic energy of a bolt's springs in state b (per metre of the model): N²/(2k) of
/// each spring at its force (at the cap, the cap's).
double bolt_elastic_energy(const BoltDef& def, const BoltState& b);

class BoltSystem {
 public:
  /// ε: the tangent of a spring at its cap, × k. It keeps the matrix positive definite where a
  /// whole cable's grout slips (its slips would otherwise slide freely: a mechanism); the force
  /// then exceeds the cap by ε·k times the step's plastic motion.
  static constexpr double kCapTangent = 1e-6;
  /// Solves of one step the modes and the Newton rounds may take before the step is cut
  /// (bolts_not_settled).
  static constexpr int kMaxRounds = 25;
  /// A step is solved again, linearised at its solution, while an axial spring's exact force
  /// there differs from the linearised one by more than this × its force (plus a nanostrain's:
  /// 1e-9·k·ℓs): the geometric nonlinearity of a segment that turns within the step.
  static constexpr double kNewtonTolerance = 1e-4;

  BoltSystem() = default;
  /// The bolts of `model`'s scene on `space` (both must outlive it).
  BoltSystem(const Model& model, const CoverSpace& space) : model_(&model), space_(&space) {}

  /// Numbers the bolts' own unknowns from first_unknown (the cover unknowns' count): one slip
  /// per point of each grouted cable; and their coupling groups.
  void number(const std::vector<BoltState>& bolts, int first_unknown);
  /// How many unknowns of their own the bolts have.
  int unknowns() const { return unknowns_; }
  /// How many coupling groups the bolts add to the pattern: one per anchored bolt (its two
  /// elements) and one per cable segment (its two elements and two slips).
  std::size_t groups() const { return group_offsets_.size() - 1; }
  /// Appends the groups' unknowns to a pattern's offsets and dofs (system_matrix.h build_pattern).
  void add_groups(std::vector<int>& offsets, std::vector<int>& dofs) const;
  /// "the slip of bolt 2 at its point 5" for an unknown of the bolts', "" for another.
  std::string describe_unknown(int unknown) const;

  /// Linearises every bolt at the step's start in `config` (the step's frames) from state s:
  /// rows, start forces, the modes of the start forces. `removed`: [me] 1 for excavated elements;
  /// a bolt with a point in one carries nothing (its slips are held).
  void begin_step(const Configuration& config, const RunState& s, const std::vector<std::uint8_t>& removed);
  /// Adds the springs in their modes to the matrix (group first_group + the spring's) and the rhs.
  void assemble(SystemMatrix& system, Eigen::VectorXd& rhs, std::size_t first_group) const;
  /// At a solution d of the step: switches each spring whose trial force contradicts its mode,
  /// breaks each anchored bolt whose |force| reached its strength, and checks the axial springs'
  /// exact forces against their linearisation (kNewtonTolerance). True: something changed or the
  /// linearisation missed, the springs are linearised again at d, and the step must be solved
  /// again.
  bool judge(const Eigen::VectorXd& d);
  /// The accepted step's results into `bolts`: forces, slips, broken and yielded flags, largest
  /// force, plastic work; their points moved with the rock (in `config`, the step's).
  void commit(const Eigen::VectorXd& d, const Configuration& config, std::vector<BoltState>& bolts) const;

  const std::vector<BoltSpring>& springs() const { return springs_; }

 private:
  double force(const BoltSpring& s, const Eigen::VectorXd& d) const;  ///< N per bolt at d, in its mode
  double stretch(const BoltSpring& s, const Eigen::VectorXd& d) const;  ///< cᵀd: a grout's slip; an axial spring's ℓ(d) − ℓs
  double across(const BoltSpring& s, const Eigen::VectorXd& d) const;   ///< c⊥ᵀd
  const Model* model_ = nullptr;
  const CoverSpace* space_ = nullptr;
  int first_unknown_ = 0;                // the bolts' first unknown
  int unknowns_ = 0;
  std::vector<int> first_slip_;          // [bolt] its first slip unknown (−1: anchored)
  std::vector<int> slips_;               // [bolt] its slip unknowns (0: anchored)
  std::vector<int> group_offsets_{0};    // [group+1] into group_dofs_
  std::vector<int> group_dofs_;
  std::vector<std::uint8_t> active_;     // [bolt] this step: no point in an excavated element
  std::vector<BoltSpring> springs_;      // this step's
  std::vector<int> dofs_;                // rows: unknowns
  std::vector<double> c_;                // rows: coefficients along the bolt (e), m per unit unknown
  std::vector<double> cp_;               // rows: across it (e⊥, less the rock's turn), m per unit unknown
};

}  // namespace nmm::solve
