// fix ID group aveforce fx fy fz [region R]   (LAMMPS fix aveforce)
// Sets each given force component of every grain of the group (inside R, if
// given) to the group's average force plus the given value: grains of equal
// mass and equal velocity then move as one. NULL leaves a component alone; a
// value is a number or v_name (equal-style, evaluated every step). The total
// force on the group becomes sum F + N (fx, fy, fz) for its N grains, as in
// LAMMPS (the value is per grain). f_ID[1..3] is the total force before.
//
// The average needs every grain's force first: a two-phase atom task. Phase 0
// adds each member's force into core's AtomSum; phase 1 (once every range has
// added) reads the total on each thread and sets the members. A two-phase
// post_force keeps the step off the pipelined plan (Simulation::run says so).
#include "core/engine/block_sum.h"
#include "core/input/style_registry.h"
#include "fixes/group_force.h"

namespace sable {

class FixAveforce : public GroupForceFix {
 public:
  FixAveforce(Simulation& s, const Args& a) : GroupForceFix(s, a, true, false) {
    two_phase_tasks = POST_FORCE;
    traits.constraint = true;
    parse_region_only(a);
  }
  void export_yade(YadeScript& s) const override { export_yade_set_forces(s, *this, true); }

  // The given values (equal-style variables: this step's) before the sum.
  void begin(FixHook) override {
    force_.evaluate(sim, args);
    sum_.begin(sim.atoms.n);
  }
  void range(FixHook, const AtomRange& r) override {
    Atoms& at = sim.atoms;
    if (r.phase == 0) {
      sum_.range(r);
      for (std::size_t i = r.lo; i < r.hi; ++i)
        if (member(i)) {
          const double v[4] = {at.f[3 * i], at.f[3 * i + 1], at.f[3 * i + 2], 1.0};
          sum_.add(r, i, v);
        }
      return;
    }
    double total[4], ave[3];
    sum_.total(total);  // every thread the same bits
    if (total[3] == 0) return;
    for (int k = 0; k < 3; ++k) ave[k] = total[k] / total[3] + (force_.active(k) ? force_.value(k) : 0.0);
    for (std::size_t i = r.lo; i < r.hi; ++i)
      if (member(i))
        for (int k = 0; k < 3; ++k)
          if (force_.active(k)) at.f[3 * i + k] = ave[k];
  }
  void end(FixHook) override { sum_.total(total_); }
  double compute_vector(int i) override { return i >= 1 && i <= 3 ? total_[i - 1] : 0.0; }

 private:
  AtomSum<4> sum_;
  double total_[4] = {0, 0, 0, 0};  // force before, grain count
};

SABLE_FIX("aveforce", FixAveforce);

}  // namespace sable
