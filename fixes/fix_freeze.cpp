// fix ID group freeze: zero the force and torque on the group after all forces
// are known (LIGGGHTS: post_force; velocities are left alone, so a frozen grain
// with a velocity keeps drifting at that velocity). f_ID[1..3] is the total force
// on the group before it was zeroed. One freeze fix at most (pair styles look it up).
#include <algorithm>
#include <array>
#include <cstring>
#include <vector>

#include "core/engine/block_sum.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/io/yade_script.h"

namespace sable {

class FixFreeze : public Fix {
 public:
  FixFreeze(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = atom_tasks = POST_FORCE;
    traits.constraint = traits.freezes_group = true;
    traits.keeps_plane = true;  // zeroes forces
    vector_size = 3;
    if (a.size() > 4) a.fail(4, "nothing after 'freeze'");
  }
  void export_yade(YadeScript& s) const override { s.freeze(*this); }  // fixed YADE bodies
  void init() override {
    bool after = false;
    for (auto& f : sim.fixes) {
      if (f.get() == this) {
        after = true;
        continue;
      }
      if (f->traits.freezes_group)
        args.fail_line("more than one fix freeze (LIGGGHTS allows one; also fix '" + f->id + "')");
      if (after && (f->hooks & POST_FORCE) && f->traits.acceleration_norm() > 0)
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
  // f_ID: the frozen grains' forces summed by core's AtomSum (the same bits for any thread count).
  void begin(FixHook) override { sum_.begin(sim.atoms.n); }
  void range(FixHook, const AtomRange& r) override {
    Atoms& at = sim.atoms;
    sum_.range(r);
    for (std::size_t i = r.lo; i < r.hi; ++i) {
      if (!(at.mask[i] & groupbit)) continue;
      sum_.add(r, i, &at.f[3 * i]);
      for (int k = 0; k < 3; ++k) at.f[3 * i + k] = at.torque[3 * i + k] = 0;
    }
  }
  void end(FixHook) override { sum_.total(f0_); }
  double compute_vector(int i) override { return i >= 1 && i <= 3 ? sim.comm.total(f0_[i - 1]) : 0.0; }

 private:
  AtomSum<3> sum_;
  double f0_[3] = {0, 0, 0};
};

SABLE_FIX("freeze", FixFreeze);

}  // namespace sable
