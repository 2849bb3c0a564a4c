// fix ID group addforce fx fy fz [every N] [region R]   (LAMMPS fix addforce)
// Adds (fx, fy, fz) to the force on each grain of the group (inside R, if
// given) after all other forces so far, every N steps. Each component is a
// number or v_name (equal- or atom-style, evaluated every step it acts);
// NULL is not allowed (as in LAMMPS). f_ID is the potential energy of the
// added field, -sum F.x (unwrapped x), and f_ID[1..3] the group's total force
// before the addition. The `energy` keyword (for minimisation) is not supported.
#include "core/engine/block_sum.h"
#include "core/input/style_registry.h"
#include "fixes/group_force.h"
#include "core/io/yade_script.h"

namespace sable {

class FixAddforce : public GroupForceFix {
 public:
  FixAddforce(Simulation& s, const Args& a) : GroupForceFix(s, a, false, true) {
    scalar_flag = 1;
    for (std::size_t i = 7; i < a.size(); i += 2) {
      if (a[i] == "every") {
        every_ = a.integer(i + 1, "a step interval > 0");
        if (every_ <= 0) a.fail(i + 1, "a step interval > 0");
      } else if (a[i] == "region") {
        region_.parse(s, a, i + 1);
      } else if (a[i] == "energy") {
        a.fail(i, "every or region ('energy' serves minimisation, which sable does not do)");
      } else {
        a.fail(i, "every or region");
      }
    }
  }
  void export_yade(YadeScript& s) const override;  // each grain's force, added each step

  void begin(FixHook) override {
    active_ = sim.step % every_ == 0;
    if (!active_) return;
    force_.evaluate(sim, args);
    sum_.begin(sim.atoms.n);
  }
  void range(FixHook, const AtomRange& r) override {
    if (!active_) return;
    Atoms& at = sim.atoms;
    sum_.range(r);
    for (std::size_t i = r.lo; i < r.hi; ++i) {
      if (!member(i)) continue;
      double* f = &at.f[3 * i];
      double xu[3], add[4];
      sim.domain.unmap(&at.x[3 * i], &at.image[3 * i], xu);
      add[0] = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double F = force_.value(k, i);
        add[0] -= F * xu[k];
        add[k + 1] = f[k];
        f[k] += F;
      }
      sum_.add(r, i, add);
    }
  }
  void end(FixHook) override {
    if (active_) sum_.total(total_);
  }
  double compute_scalar() override { return sim.comm.total(total_[0]); }
  double compute_vector(int i) override { return i >= 1 && i <= 3 ? sim.comm.total(total_[i]) : 0.0; }

 private:
  long every_ = 1;
  bool active_ = false;
  AtomSum<4> sum_;
  double total_[4] = {0, 0, 0, 0};  // energy, force before
};

void FixAddforce::export_yade(YadeScript& s) const {
  if (args.size() > 7) args.fail(7, "nothing after fx fy fz (export-yade translates no every or region)");
  std::string F[3];
  for (int k = 0; k < 3; ++k) {
    F[k] = s.force_component(args, 4 + k);
    if (F[k] == "None") F[k] = "0";
  }
  const Atoms& at = sim.atoms;
  for (std::size_t i = 0; i < at.n; ++i)
    if (at.mask[i] & groupbit)
      s.add_force("O.forces.addF(_bid(" + std::to_string(at.id[i]) + "), Vector3(" + F[0] + ", " + F[1] + ", " + F[2] +
                  "))");
}

SABLE_FIX("addforce", FixAddforce);

}  // namespace sable
