// fix ID group nve/sphere [disc]: velocity Verlet for translation and rotation
// of spheres (moment of inertia Atoms::inertia: 2/5 m r^2; `disc`, LAMMPS' 2D
// keyword, makes it 1/2 m r^2 for every user of it).
// fix ID group nve: the same for translation alone (LAMMPS fix nve: x and v;
// omega is left as it is, so with no grain turning contacts skip rotation).
//
// Each atom is updated on its own, so the loops are threaded (large systems)
// and vectorised: with group all the mask test is hoisted out of the loop.
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/engine/threads.h"
#include "core/io/yade_script.h"

namespace sable {

class FixNveSphere : public Fix {
 public:
  FixNveSphere(Simulation& s, const Args& a) : FixNveSphere(s, a, true) {}
  void export_yade(YadeScript& s) const override;  // YADE's NewtonIntegrator; fix nve refuses
  FixNveSphere(Simulation& s, const Args& a, bool spin) : Fix(s, a), spin_(spin) {
    hooks = INITIAL_INTEGRATE | FINAL_INTEGRATE;
    atom_tasks = hooks | FINAL_THEN_INITIAL;
    traits.turns_grains = spin_;
    if (!spin_ && a.size() > 4) a.fail(4, "nothing after 'nve'");
    for (std::size_t i = 4; i < a.size(); ++i)
      if (a[i] != "update" && a[i] != "dipole" && a[i] != "disc") a.fail(i, "nothing (or update dipole/disc)");
    for (std::size_t i = 4; i < a.size(); ++i)
      if (a[i] == "disc") {
        if (s.domain.dimension != 2) a.fail(i, "a 2D simulation for 'disc' (as LAMMPS requires)");
        s.atoms.inertia_factor = 0.5;
      }
  }
  // Initial: half kick, then drift, in one pass over the atoms. Final: the half
  // kick. Both, across a step boundary: one loop, the per-atom factors once.
  // The step plan composes them with its other per-atom work.
  void range(FixHook h, const AtomRange& r) override {
    if (h == FINAL_INTEGRATE) return integrate<0>(r);
    if (h == FINAL_THEN_INITIAL) return integrate<kDrift | kFinalFirst>(r);
    integrate<kDrift>(r);
  }

 private:
  static constexpr unsigned kDrift = 1, kFinalFirst = 2;
  const bool spin_;  // nve/sphere: omega from the torque; nve: omega untouched

  // Half-step velocity and spin update from force and torque (and the drift
  // x += dt v) of the atoms [lo, hi).
  template <unsigned kMode>
  void integrate(const AtomRange& r) {
    Atoms& at = sim.atoms;
    const double dt = sim.dt, h = 0.5 * sim.dt;
    const Arrays p{at.x.data(),      at.v.data(),      at.omega.data(), at.f.data(), at.torque.data(),
                   at.rmass.data(), at.radius.data(), at.mask.data(),  groupbit,      at.inertia_factor};
    for (std::size_t a = r.lo; a < r.hi; a += kBlock) {
      const std::size_t b = std::min(r.hi, a + kBlock);
      if (groupbit == 1u)  // group all (bit 0): the mask test leaves the loop
        spin_ ? block<kMode, false, true>(p, a, b, dt, h) : block<kMode, false, false>(p, a, b, dt, h);
      else
        spin_ ? block<kMode, true, true>(p, a, b, dt, h) : block<kMode, true, false>(p, a, b, dt, h);
    }
  }
  struct Arrays {
    double* x;
    double* v;
    double* w;
    double* f;
    double* t;
    const double* rmass;
    const double* radius;
    const std::uint32_t* mask;
    std::uint32_t groupbit;
    double inertia_factor;  // Atoms::inertia
  };
  // Atoms [a, b), b - a <= kBlock: the per-atom factors first, then one loop
  // over their 3 (b - a) vector components without branches, which the
  // compiler vectorises (a loop over atoms with an inner loop over x, y, z
  // it does not). Each component sees the same operations as before.
  // kMasked (a named group): grains outside it keep x, v and omega (a select,
  // not arithmetic: bit for bit).
  static constexpr std::size_t kBlock = 128;
  template <unsigned kMode, bool kMasked, bool kSpin>
  static void block(const Arrays& p, std::size_t a, std::size_t b, double dt, double h) {
    alignas(64) double hm[3 * kBlock], hw[3 * kBlock];
    alignas(64) unsigned char in[3 * kBlock];
    for (std::size_t i = a; i < b; ++i) {
      const double m = p.rmass[i], r = p.radius[i];
      const double km = h / m, kw = h / (p.inertia_factor * m * r * r);
      const bool member = !kMasked || (p.mask[i] & p.groupbit);
      for (int k = 0; k < 3; ++k) {
        const std::size_t c = 3 * (i - a) + k;
        hm[c] = km;
        hw[c] = kw;
        in[c] = member;
      }
    }
    const std::size_t n = 3 * (b - a);
    double* __restrict x = p.x + 3 * a;
    double* __restrict v = p.v + 3 * a;
    double* __restrict w = p.w + 3 * a;
    const double* __restrict f = p.f + 3 * a;
    const double* __restrict t = p.t + 3 * a;
    for (std::size_t c = 0; c < n; ++c) {
      const double fc = f[c];
      [[maybe_unused]] const double tc = t[c];
      double vc = v[c];
      [[maybe_unused]] double wc = w[c];
      if constexpr ((kMode & kFinalFirst) != 0) {  // the same two additions as two passes
        vc += hm[c] * fc;
        if constexpr (kSpin) wc += hw[c] * tc;
      }
      vc += hm[c] * fc;
      if constexpr (kSpin) wc += hw[c] * tc;
      if constexpr (kMasked) {
        v[c] = in[c] ? vc : v[c];
        if constexpr (kSpin) w[c] = in[c] ? wc : w[c];
        if constexpr ((kMode & kDrift) != 0) x[c] = in[c] ? x[c] + dt * vc : x[c];
      } else {
        v[c] = vc;
        if constexpr (kSpin) w[c] = wc;
        if constexpr ((kMode & kDrift) != 0) x[c] += dt * vc;
      }
    }
  }
};

// fix nve: translation only.
struct FixNve : FixNveSphere {
  FixNve(Simulation& s, const Args& a) : FixNveSphere(s, a, false) {}
};

void FixNveSphere::export_yade(YadeScript& s) const {
  if (!spin_) return Fix::export_yade(s);
  const Args a = args.tail(1);
  for (std::size_t k = 3; k < a.size(); ++k)
    if (a[k] != "disc") a.fail(k, "nothing (export-yade translates nve/sphere [disc])");
  s.rotate();
  s.integrate(groupbit);
}

SABLE_FIX("nve/sphere", FixNveSphere);
SABLE_FIX("nve", FixNve);

}  // namespace sable
