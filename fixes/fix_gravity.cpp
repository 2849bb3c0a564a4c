// fix ID group gravity magnitude vector x y z  (also: spherical/... not supported)
#include <cmath>

#include "core/simulation.h"
#include "core/style_registry.h"

namespace sable {

class FixGravity : public Fix {
 public:
  FixGravity(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = POST_FORCE;
    g_ = a.num(4, "the gravity magnitude (m/s^2)");
    if (a.word(5, "'vector'") != "vector") a.fail(5, "'vector' (the only gravity style supported)");
    double d[3], n = 0;
    for (int k = 0; k < 3; ++k) {
      d[k] = a.num(6 + k, "a direction component");
      n += d[k] * d[k];
    }
    if (n == 0) a.fail(6, "a non-zero direction vector");
    for (int k = 0; k < 3; ++k) acc_[k] = g_ * d[k] / std::sqrt(n);
  }
  void post_force() override {
    Atoms& at = sim.atoms;
    for (std::size_t i = 0; i < at.n; ++i) {
      if (!(at.mask[i] & groupbit)) continue;
      for (int k = 0; k < 3; ++k) at.f[3 * i + k] += at.rmass[i] * acc_[k];
    }
  }
  double acceleration() const override { return std::fabs(g_); }

 private:
  double g_ = 0, acc_[3] = {0, 0, 0};
};

SABLE_FIX("gravity", FixGravity);

}  // namespace sable
