// fix ID group freeze: zero the force and torque on the group after all forces
// are known (LIGGGHTS: post_force; velocities are left alone, so a frozen grain
// with a velocity keeps drifting at that velocity). f_ID[1..3] is the total force
// on the group before it was zeroed. One freeze fix at most (pair styles look it up).
#include <cstring>

#include "core/simulation.h"
#include "core/style_registry.h"
#include "core/threads.h"

namespace sable {

class FixFreeze : public Fix {
 public:
  FixFreeze(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = POST_FORCE;
    vector_size = 3;
    if (a.size() > 4) a.fail(4, "nothing after 'freeze'");
  }
  void init() override {
    bool after = false;
    for (auto& f : sim.fixes) {
      if (f.get() == this) {
        after = true;
        continue;
      }
      if (f->style == "freeze")
        args.fail_line("more than one fix freeze (LIGGGHTS allows one; also fix '" + f->id + "')");
      if (after && (f->hooks & POST_FORCE) && f->acceleration() > 0)
        sim.warn("fix freeze " + id + ": fix " + f->style + " '" + f->id +
                 "' is defined after it and adds force to frozen grains after they are frozen (as in LIGGGHTS); "
                 "define fix freeze after it to keep them still");
    }
    const Atoms& at = sim.atoms;
    long moving = 0;
    for (std::size_t i = 0; i < at.n; ++i)
      if (at.mask[i] & groupbit)
        for (int k = 0; k < 3; ++k)
          if (at.v[3 * i + k] != 0 || at.omega[3 * i + k] != 0) {
            ++moving;
            break;
          }
    if (moving)
      sim.warn("fix freeze " + id + ": " + std::to_string(moving) +
               " frozen grains have a velocity or spin and keep it (as in LIGGGHTS); use 'velocity " +
               sim.groups.name(group) + " set 0 0 0' to hold them still");
  }
  // Summed in fixed blocks (block_sum3): the same f_ID for any thread count;
  // small blocks keep each thread near its integrator half (atom_pass_threaded).
  void post_force() override {
    Atoms& at = sim.atoms;
    const std::uint32_t bit = groupbit;
    const auto f0 = block_sum3(at.n, 1024, 8, [&](std::size_t, std::size_t lo, std::size_t hi, double* sum) {
      for (std::size_t i = lo; i < hi; ++i) {
        if (!(at.mask[i] & bit)) continue;
        for (int k = 0; k < 3; ++k) {
          sum[k] += at.f[3 * i + k];
          at.f[3 * i + k] = 0;
          at.torque[3 * i + k] = 0;
        }
      }
    });
    for (int k = 0; k < 3; ++k) f0_[k] = f0[k];
  }
  double compute_vector(int i) override { return i >= 1 && i <= 3 ? f0_[i - 1] : 0.0; }

 private:
  double f0_[3] = {0, 0, 0};
};

SABLE_FIX("freeze", FixFreeze);

}  // namespace sable
