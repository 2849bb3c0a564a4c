// compute ID group erotate/sphere [update_on_run_end yes|no] [halfstep]:
// rotational kinetic energy sum 1/2 I w^2 with I = Atoms::inertia (2/5 m r^2,
// also in 2D as LIGGGHTS; 1/2 m r^2 for disks), a global scalar.
#include "computes/kinetic_energy.h"
#include "core/input/style_registry.h"

namespace sable {

class ComputeErotateSphere : public GrainEnergyCompute {
 public:
  using GrainEnergyCompute::GrainEnergyCompute;
  double compute_scalar() override {
    const double dt = halfstep_ ? sim.dt : 0.0;
    return half_sum([dt](const Atoms& a, std::size_t i) {
      const double inertia = a.inertia(i);
      if (inertia <= 0.0) return 0.0;  // point particles carry no rotational energy
      const double h = 0.5 * dt / inertia;  // w(t + dt/2) = w + dt/2 T/I
      double w2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double w = a.omega[3 * i + k] + h * a.torque[3 * i + k];
        w2 += w * w;
      }
      return inertia * w2;
    });
  }
};

SABLE_COMPUTE("erotate/sphere", ComputeErotateSphere);

}  // namespace sable
