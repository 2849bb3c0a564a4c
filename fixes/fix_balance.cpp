// fix ID group balance Nfreq thresh shift dimstr Niter stopthresh (LAMMPS): every Nfreq
// steps, `balance`'s shift (core/input/command_balance.cpp) when the imbalance factor
// exceeds thresh; the next step rebuilds, which moves the grains. f_ID: the imbalance
// factor after the last check (1 on one rank); f_ID[1] the same, f_ID[2] the one before
// it, f_ID[3] how many times the cuts moved. The group is ignored (LAMMPS).
#include "core/engine/simulation.h"
#include "core/input/command_balance.h"
#include "core/input/style_registry.h"

namespace sable {

class FixBalance : public Fix {
 public:
  FixBalance(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = END_OF_STEP;
    nevery = static_cast<int>(a.integer(3 + 1, "the balance period Nfreq (steps)"));
    if (nevery < 1) a.fail(4, "a period Nfreq >= 1");
    shift_ = parse_balance_shift(s, a, 5);
    scalar_flag = true;
    vector_size = 3;
  }
  void end_of_step() override {
    const auto [before, after] = sim.comm.rebalance(sim, shift_.thresh, shift_.dims);
    last_ = {before, after};
    if (after == before) return;
    ++moves_;
    sim.neighbor.last_build_step = -1;  // every rank rebuilds at the next step: the grains move
  }
  double compute_scalar() override { return last_[1]; }
  double compute_vector(int i) override { return i == 1 ? last_[1] : i == 2 ? last_[0] : i == 3 ? moves_ : 0.0; }

 private:
  BalanceShift shift_;
  std::array<double, 2> last_{1, 1};
  double moves_ = 0;
};

SABLE_FIX("balance", FixBalance);

}  // namespace sable
