// compute ID group erotate/sphere [update_on_run_end yes|no] [halfstep]:
// rotational kinetic energy sum 1/2 I w^2 with I = Atoms::inertia (2/5 m r^2,
// also in 2D as LIGGGHTS; 1/2 m r^2 for disks), a global scalar.
#include "core/simulation.h"
#include "core/style_registry.h"

namespace sable {

class ComputeErotateSphere : public Compute {
 public:
  ComputeErotateSphere(Simulation& s, const Args& a) : Compute(s, a) {
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
    double e = 0.0;
    for (std::size_t i = 0; i < a.n; ++i) {
      if (!(a.mask[i] & groupbit)) continue;
      const double inertia = a.inertia(i);
      if (inertia <= 0.0) continue;  // point particles carry no rotational energy
      const double h = halfstep_ ? 0.5 * sim.dt / inertia : 0.0;  // w(t + dt/2) = w + dt/2 T/I
      double w2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double w = a.omega[3 * i + k] + h * a.torque[3 * i + k];
        w2 += w * w;
      }
      e += inertia * w2;
    }
    return 0.5 * e;
  }

 private:
  bool halfstep_ = false;
};

SABLE_COMPUTE("erotate/sphere", ComputeErotateSphere);

}  // namespace sable
