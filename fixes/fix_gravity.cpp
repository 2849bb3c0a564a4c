// fix ID group gravity magnitude vector x y z  (also: spherical/... not supported)
#include <algorithm>
#include <cmath>

#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/engine/threads.h"
#include "core/io/yade_script.h"

namespace sable {

class FixGravity : public Fix {
 public:
  FixGravity(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = atom_tasks = POST_FORCE;
    g_ = a.num(4, "the gravity magnitude (m/s^2)");
    if (a.word(5, "'vector'") != "vector") a.fail(5, "'vector' (the only gravity style supported)");
    double d[3], n = 0;
    for (int k = 0; k < 3; ++k) {
      d[k] = a.num(6 + k, "a direction component");
      n += d[k] * d[k];
    }
    if (n == 0) a.fail(6, "a non-zero direction vector");
    for (int k = 0; k < 3; ++k) acc_[k] = g_ * d[k] / std::sqrt(n);
    traits.accelerates = true;
    std::copy(acc_, acc_ + 3, traits.acceleration);
  }
  void range(FixHook, const AtomRange& r) override {
    const std::size_t lo = r.lo, hi = r.hi;
    Atoms& at = sim.atoms;
    double* f = at.f.data();
    const double* rmass = at.rmass.data();
    const std::uint32_t* mask = at.mask.data();
    const std::uint32_t bit = groupbit;
    const bool all = bit == 1u;  // group all: the mask test leaves the loop, which vectorises
    const double a0 = acc_[0], a1 = acc_[1], a2 = acc_[2];
    for (std::size_t i = lo; i < hi; ++i) {
      if (!all && !(mask[i] & bit)) continue;
      f[3 * i] += rmass[i] * a0;
      f[3 * i + 1] += rmass[i] * a1;
      f[3 * i + 2] += rmass[i] * a2;
    }
  }
  // YADE's NewtonIntegrator gravity, which acts on every body.
  void export_yade(YadeScript& s) const override {
    if (groupbit != 1u) args.tail(1).fail(1, "all (YADE's gravity acts on every body)");
    s.add_gravity(acc_);
  }

 private:
  double g_ = 0, acc_[3] = {0, 0, 0};
};

SABLE_FIX("gravity", FixGravity);

}  // namespace sable
