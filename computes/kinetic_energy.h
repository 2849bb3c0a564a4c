#pragma once
// What the kinetic-energy computes share: ke and erotate/sphere (a sum over
// the group's grains, with LIGGGHTS' keywords), ke/multisphere and
// erotate/multisphere (fix multisphere's body sums). Global scalars.
#include <string>

#include "core/engine/simulation.h"
#include "fixes/fix_multisphere.h"

namespace sable {

// compute ID group ke|erotate/sphere [update_on_run_end yes|no] [halfstep]
class GrainEnergyCompute : public Compute {
 public:
  GrainEnergyCompute(Simulation& s, const Args& a) : Compute(s, a) {
    scalar_flag = true;
    for (std::size_t i = 4; i < a.size(); ++i) {
      if (a[i] == "halfstep") halfstep_ = true;
      else if (a[i] == "update_on_run_end") a.yes_no(++i, "yes or no");  // lazy evaluation makes it moot
      else a.fail(i, "halfstep or update_on_run_end yes|no");
    }
  }
  // Atoms may have been changed (set, velocity) since a run ended on this same step.
  void init() override { invoked_step = -1; }

 protected:
  bool halfstep_ = false;
  // 1/2 the sum of term(i) over the group's grains.
  template <class Term>
  double half_sum(Term term) const {
    const Atoms& a = sim.atoms;
    double e = 0.0;
    for (std::size_t i = 0; i < a.n; ++i)
      if (a.mask[i] & groupbit) e += term(a, i);
    return 0.5 * sim.comm.total(e);
  }
};

// compute ID group ke/multisphere|erotate/multisphere: fix multisphere's sum over its
// bodies (LIGGGHTS 3.8: the group is ignored).
template <double (FixMultisphere::*Energy)() const>
class BodyEnergyCompute : public Compute {
 public:
  BodyEnergyCompute(Simulation& s, const Args& a) : Compute(s, a) {
    scalar_flag = true;
    if (a.size() > 4) a.fail(4, "nothing more (compute " + style + " takes no keywords)");
  }
  void init() override {
    invoked_step = -1;
    fix_ = sim.find_fix_style<FixMultisphere>();
    if (!fix_) args.fail_line("compute " + style + " needs a fix multisphere");
  }
  double compute_scalar() override { return (fix_->*Energy)(); }

 private:
  FixMultisphere* fix_ = nullptr;
};

}  // namespace sable
