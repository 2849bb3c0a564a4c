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
    const Arrays p{at.x.data(), at.v.data(), at.omega.data(), at.f.data(), at.torque.data(), at.rmass.data(),
                   at.radius.data(), fuse.accel};
    if (groupbit == 1u) {  // group all (bit 0): every atom, in vectorised blocks
      for (std::size_t a = lo; a < hi; a += kBlock) block<kMode>(p, a, std::min(hi, a + kBlock), dt, h);
      return;
    }
    const std::uint32_t* mask = at.mask.data();
    for (std::size_t i = lo; i < hi; ++i)
      if (mask[i] & groupbit) block<kMode>(p, i, i + 1, dt, h);
  }
  struct Arrays {
    double* x;
    double* v;
    double* w;
    double* f;
    double* t;
    const double* rmass;
    const double* radius;
    const double* accel;  // kAccel: the folded gravity
  };
  // Atoms [a, b), b - a <= kBlock: the per-atom factors first, then one loop
  // over their 3 (b - a) vector components without branches, which the
  // compiler vectorises (a loop over atoms with an inner loop over x, y, z
  // it does not). Each component sees the same operations as before.
  // kFinalFirst: the same two additions as a final pass followed by an
  // initial one (same forces, same order), so the same bits; kAccel: gravity's
  // addition to the force first, as its own pass would have made it.
  static constexpr std::size_t kBlock = 128;
  template <unsigned kMode>
  static void block(const Arrays& p, std::size_t a, std::size_t b, double dt, double h) {
    alignas(64) double hm[3 * kBlock], hw[3 * kBlock], ma[3 * kBlock];
    for (std::size_t i = a; i < b; ++i) {
      const double m = p.rmass[i], r = p.radius[i];
      const double km = h / m, kw = h / (0.4 * m * r * r);
      for (int k = 0; k < 3; ++k) {
        const std::size_t c = 3 * (i - a) + k;
        hm[c] = km;
        hw[c] = kw;
        if constexpr ((kMode & kAccel) != 0) ma[c] = m * p.accel[k];
      }
    }
    const std::size_t n = 3 * (b - a);
    double* __restrict x = p.x + 3 * a;
    double* __restrict v = p.v + 3 * a;
    double* __restrict w = p.w + 3 * a;
    double* __restrict f = p.f + 3 * a;
    double* __restrict t = p.t + 3 * a;
    for (std::size_t c = 0; c < n; ++c) {
      double fc = f[c];
      const double tc = t[c];
      if constexpr ((kMode & kAccel) != 0) {  // fix gravity's own addition, stored as it stores it
        fc += ma[c];
        f[c] = fc;
      }
      double vc = v[c], wc = w[c];
      if constexpr ((kMode & kFinalFirst) != 0) {
        vc += hm[c] * fc;
        wc += hw[c] * tc;
      }
      vc += hm[c] * fc;
      wc += hw[c] * tc;
      v[c] = vc;
      w[c] = wc;
      if constexpr ((kMode & kDrift) != 0) x[c] += dt * vc;
      if constexpr ((kMode & kClear) != 0) f[c] = t[c] = 0.0;
    }
  }
};

SABLE_FIX("nve/sphere", FixNveSphere);

}  // namespace sable
