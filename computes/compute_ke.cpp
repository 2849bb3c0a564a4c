// compute ID group ke [update_on_run_end yes|no] [halfstep]: translational
// kinetic energy sum 1/2 m v^2 of the group (LIGGGHTS compute ke), a global scalar.
#include "core/simulation.h"
#include "core/style_registry.h"

namespace sable {

class ComputeKE : public Compute {
 public:
  ComputeKE(Simulation& s, const Args& a) : Compute(s, a) {
    scalar_flag = true;
    for (std::size_t i = 4; i < a.size(); ++i) {
      if (a[i] == "halfstep") halfstep_ = true;
      else if (a[i] == "update_on_run_end") a.yes_no(++i, "yes or no");  // lazy evaluation makes it moot
      else a.fail(i, "halfstep or update_on_run_end yes|no");
    }
  }
  // Atoms may have been changed (set, velocity) since a run ended on this same step.
  void init() override { invoked_step = -1; }

  double compute_scalar() override {
    const Atoms& a = sim.atoms;
    const double h = halfstep_ ? 0.5 * sim.dt : 0.0;  // v(t + dt/2) = v + dt/2 f/m
    double ke = 0.0;
    for (std::size_t i = 0; i < a.n; ++i) {
      if (!(a.mask[i] & groupbit)) continue;
      double v2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double v = a.v[3 * i + k] + h * a.f[3 * i + k] / a.rmass[i];
        v2 += v * v;
      }
      ke += a.rmass[i] * v2;
    }
    return 0.5 * ke;
  }

 private:
  bool halfstep_ = false;
};

SABLE_COMPUTE("ke", ComputeKE);

}  // namespace sable
