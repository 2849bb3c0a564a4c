// fix ID group aveforce fx fy fz [region R]   (LAMMPS fix aveforce)
// Sets each given force component of every grain of the group (inside R, if
// given) to the group's average force plus the given value: grains of equal
// mass and equal velocity then move as one. NULL leaves a component alone; a
// value is a number or v_name (equal-style, evaluated every step). The total
// force on the group becomes sum F + N (fx, fy, fz) for its N grains, as in
// LAMMPS (the value is per grain). f_ID[1..3] is the total force before.
//
// The average needs every grain's force first, so this is not a per-atom task:
// two passes over the atoms after the force pass (a BlockSum, then the set),
// which keeps the step off the pipelined plan (Simulation::run says so).
#include "core/engine/block_sum.h"
#include "core/input/style_registry.h"
#include "core/engine/threads.h"
#include "fixes/group_force.h"

namespace sable {

class FixAveforce : public Fix {
 public:
  FixAveforce(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = POST_FORCE;
    vector_size = 3;
    if (a.size() < 7) a.fail(a.size(), "three force components fx fy fz (number, v_name or NULL) after 'aveforce'");
    force_.parse(a, 4, true, false);
    for (std::size_t i = 7; i < a.size(); i += 2) {
      if (a[i] != "region") a.fail(i, "region");
      region_.parse(s, a, i + 1);
    }
  }
  void init() override {
    force_.check(sim, args);
    region_.init(sim, args);
  }
  bool keeps_plane() const override { return force_.keeps_plane(); }
  void export_yade(YadeScript& s) const override { export_yade_set_forces(s, *this, true); }

  void post_force() override {
    Atoms& at = sim.atoms;
    sum_.begin(at.n, kBlock, atom_pass_threads());
    at.for_ranges([&](int t, std::size_t lo, std::size_t hi) {
      sum_.range(t, lo);
      for (std::size_t i = lo; i < hi; ++i) {
        if (!member(i)) continue;
        const double v[4] = {at.f[3 * i], at.f[3 * i + 1], at.f[3 * i + 2], 1.0};
        sum_.add(t, i, v);
      }
    });
    sum_.finish(total_);
    const double count = total_[3];
    if (count == 0) return;
    force_.evaluate(sim, args);
    double ave[3];
    for (int k = 0; k < 3; ++k) ave[k] = total_[k] / count + (force_.active(k) ? force_.value(k) : 0.0);
    at.for_ranges([&](int, std::size_t lo, std::size_t hi) {
      for (std::size_t i = lo; i < hi; ++i) {
        if (!member(i)) continue;
        for (int k = 0; k < 3; ++k)
          if (force_.active(k)) at.f[3 * i + k] = ave[k];
      }
    });
  }
  double compute_vector(int i) override { return i >= 1 && i <= 3 ? total_[i - 1] : 0.0; }

 private:
  static constexpr std::size_t kBlock = 1024;
  ForceComponents force_;
  RegionOption region_;
  BlockSum<4> sum_;
  double total_[4] = {0, 0, 0, 0};  // force before, grain count

  bool member(std::size_t i) const {
    return (sim.atoms.mask[i] & groupbit) && region_.admits(&sim.atoms.x[3 * i]);
  }
};

SABLE_FIX("aveforce", FixAveforce);

}  // namespace sable
