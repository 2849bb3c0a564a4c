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
    Arrays p{at.x.data(), at.v.data(), at.omega.data(), at.f.data(), at.torque.data(), at.rmass.data(),
             at.radius.data()};
    const std::uint32_t* mask = at.mask.data();
    const std::uint32_t bit = groupbit;
    const long nn = static_cast<long>(n);
    const bool threads = loop_thread_count(n, 8) > 1;
    if (bit == 1u) {  // group all (bit 0): every atom, a loop without a test (vectorised)
#pragma omp parallel for schedule(static) if (threads)
      for (long i = 0; i < nn; ++i) step<kDrift>(p, i, dt, h);
    } else {
#pragma omp parallel for schedule(static) if (threads)
      for (long i = 0; i < nn; ++i)
        if (mask[i] & bit) step<kDrift>(p, i, dt, h);
    }
  }
  struct Arrays {
    double* __restrict x;
    double* __restrict v;
    double* __restrict w;
    const double* __restrict f;
    const double* __restrict t;
    const double* __restrict rmass;
    const double* __restrict radius;
  };
  template <bool kDrift>
  [[gnu::always_inline]] static inline void step(const Arrays& p, long i, double dt, double h) {
    const double m = p.rmass[i], r = p.radius[i];
    const double hm = h / m, hi = h / (0.4 * m * r * r);
    for (int k = 0; k < 3; ++k) {
      p.v[3 * i + k] += hm * p.f[3 * i + k];
      p.w[3 * i + k] += hi * p.t[3 * i + k];
      if constexpr (kDrift) p.x[3 * i + k] += dt * p.v[3 * i + k];
    }
  }
};

SABLE_FIX("nve/sphere", FixNveSphere);

}  // namespace sable
