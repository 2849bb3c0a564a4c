// compute ID group ke [update_on_run_end yes|no] [halfstep]: translational
// kinetic energy sum 1/2 m v^2 of the group (LIGGGHTS compute ke), a global scalar.
#include "computes/kinetic_energy.h"
#include "core/input/style_registry.h"

namespace sable {

class ComputeKE : public GrainEnergyCompute {
 public:
  using GrainEnergyCompute::GrainEnergyCompute;
  double compute_scalar() override {
    const double h = halfstep_ ? 0.5 * sim.dt : 0.0;  // v(t + dt/2) = v + dt/2 f/m
    return half_sum([h](const Atoms& a, std::size_t i) {
      double v2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double v = a.v[3 * i + k] + h * a.f[3 * i + k] / a.rmass[i];
        v2 += v * v;
      }
      return a.rmass[i] * v2;
    });
  }
};

SABLE_COMPUTE("ke", ComputeKE);

}  // namespace sable
