// fix ID group nve/sphere: velocity Verlet for translation and rotation of
// spheres (moment of inertia 2/5 m r^2). Rotation is skipped when no grain
// can spin (frozen-rotation scenes pay nothing for it).
//
// Each atom is updated on its own, so the loops are threaded (large systems)
// and vectorised: with group all the mask test is hoisted out of the loop.
#include "core/simulation.h"
#include "core/style_registry.h"
#include "core/threads.h"

namespace sable {

class FixNveSphere : public Fix {
 public:
  FixNveSphere(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = INITIAL_INTEGRATE | FINAL_INTEGRATE;
    for (std::size_t i = 4; i < a.size(); ++i)
      if (a[i] != "update" && a[i] != "dipole" && a[i] != "disc") a.fail(i, "nothing (or update dipole/disc)");
  }
  // Half kick, then drift, in one pass over the atoms.
  void initial_integrate() override { integrate<true>(); }
  void final_integrate() override { integrate<false>(); }

 private:
  // Half-step velocity and spin update from force and torque (and the drift x += dt v).
  template <bool kDrift>
  void integrate() {
    Atoms& at = sim.atoms;
    const std::size_t n = at.n;
    const double dt = sim.dt, h = 0.5 * sim.dt;
    double* x = at.x.data();
    double* v = at.v.data();
    double* w = at.omega.data();
    const double* f = at.f.data();
    const double* t = at.torque.data();
    const double* rmass = at.rmass.data();
    const double* radius = at.radius.data();
    const std::uint32_t* mask = at.mask.data();
    const std::uint32_t bit = groupbit;
    const bool all = bit == 1u;  // group all (bit 0): every atom
    const long nn = static_cast<long>(n);
#pragma omp parallel for schedule(static) if (loop_thread_count(n, 8) > 1)
    for (long i = 0; i < nn; ++i) {
      if (!all && !(mask[i] & bit)) continue;
      const double m = rmass[i], r = radius[i];
      const double hm = h / m, hi = h / (0.4 * m * r * r);
      for (int k = 0; k < 3; ++k) {
        v[3 * i + k] += hm * f[3 * i + k];
        w[3 * i + k] += hi * t[3 * i + k];
        if constexpr (kDrift) x[3 * i + k] += dt * v[3 * i + k];
      }
    }
  }
};

SABLE_FIX("nve/sphere", FixNveSphere);

}  // namespace sable
