// fix ID group nve/sphere: velocity Verlet for translation and rotation of
// spheres (moment of inertia 2/5 m r^2).
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
  // Half kick, then drift, in one pass over the atoms; fused (Simulation::run)
  // with last step's final half kick (and gravity) before it and the force
  // clear after it.
  void initial_integrate() override {
    sim.atoms.for_ranges([&](int t, std::size_t lo, std::size_t hi) { initial_integrate_range(t, lo, hi); });
  }
  void initial_integrate_range(int, std::size_t lo, std::size_t hi) override {
    const bool accel = fuse.final && fuse.accel;
    const unsigned m = kDrift | (fuse.final ? kFinalFirst : 0u) | (fuse.clear ? kClear : 0u) | (accel ? kAccel : 0u);
    switch (m) {
      case kDrift: return integrate<kDrift>(lo, hi);
      case kDrift | kFinalFirst: return integrate<kDrift | kFinalFirst>(lo, hi);
      case kDrift | kClear: return integrate<kDrift | kClear>(lo, hi);
      case kDrift | kFinalFirst | kClear: return integrate<kDrift | kFinalFirst | kClear>(lo, hi);
      case kDrift | kFinalFirst | kAccel: return integrate<kDrift | kFinalFirst | kAccel>(lo, hi);
      default: return integrate<kDrift | kFinalFirst | kClear | kAccel>(lo, hi);
    }
  }
  void final_integrate() override {
    sim.atoms.for_ranges([&](int, std::size_t lo, std::size_t hi) { integrate<0>(lo, hi); });
  }
  // Fusion needs every atom integrated (the clear must reach them all).
  bool can_fuse() const override { return groupbit == 1u; }

 private:
  static constexpr unsigned kDrift = 1, kFinalFirst = 2, kClear = 4, kAccel = 8;

  // Half-step velocity and spin update from force and torque (and the drift
  // x += dt v) of the atoms [lo, hi).
  template <unsigned kMode>
  void integrate(std::size_t lo, std::size_t hi) {
    Atoms& at = sim.atoms;
    const double dt = sim.dt, h = 0.5 * sim.dt;
    Arrays p{at.x.data(), at.v.data(), at.omega.data(), at.f.data(), at.torque.data(), at.rmass.data(),
             at.radius.data(), fuse.accel};
    const std::uint32_t* mask = at.mask.data();
    const std::uint32_t bit = groupbit;
    if (bit == 1u) {  // group all (bit 0): every atom, a loop without a test (vectorised)
      for (std::size_t i = lo; i < hi; ++i) step<kMode>(p, i, dt, h);
    } else {
      for (std::size_t i = lo; i < hi; ++i)
        if (mask[i] & bit) step<kMode>(p, i, dt, h);
    }
  }
  struct Arrays {
    double* __restrict x;
    double* __restrict v;
    double* __restrict w;
    double* __restrict f;
    double* __restrict t;
    const double* __restrict rmass;
    const double* __restrict radius;
    const double* accel;  // kAccel: the folded gravity
  };
  // kFinalFirst: the same two additions as a final pass followed by an initial
  // one (same forces, same order), so the same bits; kAccel: gravity's addition
  // to the force first, as its own pass would have made it.
  template <unsigned kMode>
  [[gnu::always_inline]] static inline void step(const Arrays& p, std::size_t i, double dt, double h) {
    const double m = p.rmass[i], r = p.radius[i];
    const double hm = h / m, hi = h / (0.4 * m * r * r);
    for (int k = 0; k < 3; ++k) {
      double f = p.f[3 * i + k];
      const double t = p.t[3 * i + k];
      if constexpr ((kMode & kAccel) != 0) {  // fix gravity's own addition, stored as it stores it
        f += m * p.accel[k];
        p.f[3 * i + k] = f;
      }
      double v = p.v[3 * i + k], w = p.w[3 * i + k];
      if constexpr ((kMode & kFinalFirst) != 0) {
        v += hm * f;
        w += hi * t;
      }
      v += hm * f;
      w += hi * t;
      p.v[3 * i + k] = v;
      p.w[3 * i + k] = w;
      if constexpr ((kMode & kDrift) != 0) p.x[3 * i + k] += dt * v;
      if constexpr ((kMode & kClear) != 0) p.f[3 * i + k] = p.t[3 * i + k] = 0.0;
    }
  }
};

SABLE_FIX("nve/sphere", FixNveSphere);

}  // namespace sable
