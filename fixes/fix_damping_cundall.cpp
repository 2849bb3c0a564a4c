// fix ID group damping/cundall alpha: Cundall's local non-viscous damping
// (see fixes/fix_damping_cundall.h for the law and the fix order).
#include "fixes/fix_damping_cundall.h"

#include <cmath>

#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

FixDampingCundall::FixDampingCundall(Simulation& s, const Args& a) : Fix(s, a) {
  hooks = atom_tasks = POST_FORCE;
  traits.keeps_plane = true;  // a zero component stays zero
  alpha_ = a.num(4, "the damping coefficient alpha (0 <= alpha < 1)");
  if (!(alpha_ >= 0 && alpha_ < 1)) a.fail(4, "a damping coefficient alpha with 0 <= alpha < 1");
  if (a.size() > 5) a.fail(5, "nothing after alpha");
}

void FixDampingCundall::init() {
  for (const Fix* f : later_force_fixes())
    sim.warn("fix damping/cundall " + id + ": fix " + f->style + " '" + f->id +
             "' is defined after it, so its force is not damped; define fix damping/cundall after every fix "
             "that adds force (gravity, walls) and before enforce2d and freeze");
}

void FixDampingCundall::begin(FixHook) {
  if (!keep_) return;
  added_.assign(3 * sim.atoms.n, 0.0);
  added_step_ = sim.step;
}

// YADE's cundallDamp2nd on the force (accel = F/m) and the torque (F -> T,
// m -> I): the sign of the component against the velocity at the force's time.
// Grains of rigid bodies (a nonzero pair-exclusion key) are left to their body.
void FixDampingCundall::range(FixHook, const AtomRange& r) {
  Atoms& at = sim.atoms;
  const double a = alpha_, h = 0.5 * sim.dt;
  double* kept = keep_ ? added_.data() : nullptr;
  const double* member = at.pair_exclusion >= 0 ? at.column(at.pair_exclusion).data() : nullptr;
  for (std::size_t i = r.lo; i < r.hi; ++i) {
    if (!(at.mask[i] & groupbit) || (member && member[i] != 0.0)) continue;
    const double m = at.rmass[i], inertia = at.inertia(i);
    for (int k = 0; k < 3; ++k) {
      double& f = at.f[3 * i + k];
      const double df = law(a, f, at.v[3 * i + k] + h * f / m);
      f += df;
      if (kept) kept[3 * i + k] = df;
      double& t = at.torque[3 * i + k];
      t += law(a, t, at.omega[3 * i + k] + h * t / inertia);
    }
  }
}

const double* FixDampingCundall::added(std::size_t natoms, long step) const {
  return keep_ && added_step_ == step && added_.size() == 3 * natoms ? added_.data() : nullptr;
}

SABLE_FIX("damping/cundall", FixDampingCundall);

}  // namespace sable
