// compute ID group ke/multisphere: the translational kinetic energy 1/2 M vcm^2
// summed over the bodies of fix multisphere (LIGGGHTS 3.8: the group is ignored), a global scalar.
#include "core/simulation.h"
#include "core/style_registry.h"
#include "fixes/fix_multisphere.h"

namespace sable {

class ComputeKeMultisphere : public Compute {
 public:
  ComputeKeMultisphere(Simulation& s, const Args& a) : Compute(s, a) {
    scalar_flag = true;
    if (a.size() > 4) a.fail(4, "nothing more (compute ke/multisphere takes no keywords)");
  }
  void init() override {
    invoked_step = -1;
    fix_ = sim.find_fix_style<FixMultisphere>();
    if (!fix_) args.fail_line("compute ke/multisphere needs a fix multisphere");
  }
  double compute_scalar() override { return fix_->kinetic_energy(); }

 private:
  FixMultisphere* fix_ = nullptr;
};

SABLE_COMPUTE("ke/multisphere", ComputeKeMultisphere);

}  // namespace sable
