// crack_tips.csv: the stress intensity factors of every crack tip inside a body at every output
// step (docs/interface.md "Crack tips and LEFM", docs/crack-tips.md), for every run
// that has such a tip, whether or not its rock can break; summary.json fracture.tips.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solver/fracture/crack_tips.h"
#include "solver/output/run_driver.h"

namespace nmm::solve {

/// One tip at one step, as crack_tips.csv has it.
struct TipReading {
  int tip = -1;          ///< its number (crack_tips.h)
  double x = 0, y = 0;   ///< m, where the tip is now
  double k1 = 0, k2 = 0; ///< Pa·√m, K_I (> 0 opens) and K_II
  double angle_deg = 0;  ///< deg counter-clockwise from +x: the maximum tangential stress direction
  double radius = 0;     ///< m, the domain the integral ran over
};

/// The tips of the run's state now and their K (interaction_integral.h), numbered by `finder`.
std::vector<TipReading> read_crack_tips(const RunView& run, CrackTipFinder& finder);

class CrackTipOutput : public StepObserver {
 public:
  CrackTipOutput(std::string dir, std::int64_t output_every);
  void start(const RunView& run) override { record(run, 0); }
  void after_step(const RunView& run, std::int64_t n, bool last) override {
    if (n % output_every_ == 0 || last) record(run, n);
  }
  void finish(const RunView& run, const Outcome&, std::int64_t done) override;
  /// summary.json fracture.tips: how many tips the run ends with (only for a run with tips or
  /// with a fracture block).
  void summarise(nlohmann::json& summary) const override;

 private:
  void record(const RunView& run, std::int64_t n);

  std::string dir_;
  std::int64_t output_every_;
  std::int64_t last_ = -1;
  CrackTipFinder finder_;
  std::string rows_;
  bool any_ = false;   // a tip was found at some output step
  int tips_now_ = 0;   // at the last output step
};

}  // namespace nmm::solve
