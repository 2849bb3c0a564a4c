// fix ID group momentum N [linear xflag yflag zflag] [rescale]  (LAMMPS/LIGGGHTS)
// Every N steps, at the end of the step, the group's centre-of-mass velocity is
// taken out of each of its grains along the flagged axes (linear 1 1 1 when the
// keyword is absent); `rescale` then scales the group's velocities back to the
// translational kinetic energy they had. `angular` is refused (sable does not
// remove the group's angular momentum). Sums run over the atoms in order: the
// same bits for any thread count.
#include <cmath>

#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

class FixMomentum : public Fix {
 public:
  FixMomentum(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = END_OF_STEP;
    const long n = a.integer(4, "the period N (steps)");
    if (n < 1) a.fail(4, "a period N >= 1");
    nevery = static_cast<int>(n);
    bool linear_given = false;
    for (std::size_t i = 5; i < a.size();) {
      if (a[i] == "linear") {
        for (int k = 0; k < 3; ++k) {
          const long f = a.integer(i + 1 + k, "a flag 0 or 1");
          if (f != 0 && f != 1) a.fail(i + 1 + k, "a flag 0 or 1");
          flag_[k] = f == 1;
        }
        linear_given = true;
        i += 4;
      } else if (a[i] == "rescale") {
        rescale_ = true;
        ++i;
      } else if (a[i] == "angular") {
        a.fail(i, "linear or rescale (sable does not remove the angular momentum)");
      } else {
        a.fail(i, "linear xflag yflag zflag, or rescale");
      }
    }
    if (!linear_given) flag_[0] = flag_[1] = flag_[2] = true;
  }

  void end_of_step() override {
    Atoms& at = sim.atoms;
    double m = 0, p[3] = {0, 0, 0}, ke = 0;
    for (std::size_t i = 0; i < at.n; ++i) {
      if (!(at.mask[i] & groupbit)) continue;
      m += at.rmass[i];
      for (int k = 0; k < 3; ++k) {
        p[k] += at.rmass[i] * at.v[3 * i + k];
        ke += at.rmass[i] * at.v[3 * i + k] * at.v[3 * i + k];
      }
    }
    if (!(m > 0)) return;
    double after = 0;
    for (std::size_t i = 0; i < at.n; ++i) {
      if (!(at.mask[i] & groupbit)) continue;
      for (int k = 0; k < 3; ++k) {
        if (flag_[k]) at.v[3 * i + k] -= p[k] / m;
        after += at.rmass[i] * at.v[3 * i + k] * at.v[3 * i + k];
      }
    }
    if (!rescale_ || !(after > 0)) return;
    const double s = std::sqrt(ke / after);
    for (std::size_t i = 0; i < at.n; ++i)
      if (at.mask[i] & groupbit)
        for (int k = 0; k < 3; ++k) at.v[3 * i + k] *= s;
  }

 private:
  bool flag_[3] = {false, false, false};
  bool rescale_ = false;
};

SABLE_FIX("momentum", FixMomentum);

}  // namespace sable
