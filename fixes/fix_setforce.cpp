// fix ID group setforce fx fy fz [region R]   (LAMMPS fix setforce)
// Sets each given force component on each grain of the group (inside R, if
// given) after all other forces so far; NULL leaves a component alone. Each
// component is a number, NULL or v_name (equal- or atom-style, evaluated every
// step). Torques are left alone (LAMMPS). f_ID[1..3] is the group's total force
// before it was set (the grains inside R).
#include "core/engine/block_sum.h"
#include "core/input/style_registry.h"
#include "fixes/group_force.h"

namespace sable {

class FixSetforce : public GroupForceFix {
 public:
  FixSetforce(Simulation& s, const Args& a) : GroupForceFix(s, a, true, true) {
    traits.constraint = true;
    parse_region_only(a);
  }
  void export_yade(YadeScript& s) const override { export_yade_set_forces(s, *this, false); }

  void begin(FixHook) override {
    force_.evaluate(sim, args);
    sum_.begin(sim.atoms.n);
  }
  void range(FixHook, const AtomRange& r) override {
    Atoms& at = sim.atoms;
    sum_.range(r);
    for (std::size_t i = r.lo; i < r.hi; ++i) {
      if (!member(i)) continue;
      double* f = &at.f[3 * i];
      sum_.add(r, i, f);
      for (int k = 0; k < 3; ++k)
        if (force_.active(k)) f[k] = force_.value(k, i);
    }
  }
  void end(FixHook) override { sum_.total(total_); }
  double compute_vector(int i) override { return i >= 1 && i <= 3 ? sim.comm.total(total_[i - 1]) : 0.0; }

 private:
  AtomSum<3> sum_;
  double total_[3] = {0, 0, 0};
};

SABLE_FIX("setforce", FixSetforce);

}  // namespace sable
