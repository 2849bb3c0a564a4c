#pragma once
// fix ID group damping/cundall alpha (sable addition; LIGGGHTS has no such
// style): Cundall's local non-viscous damping, as YADE's NewtonIntegrator
// applies it (cundallDamp2nd, damping = alpha, gravity damped): each component
// of a grain's force shrinks by alpha times its magnitude when it pushes along
// the grain's velocity, and grows by as much when it pushes against it,
//   F_k -= alpha |F_k| sign(F_k u_k),   u = v + dt/2 F/m,
// where v is the half-step velocity the force pass sees and u estimates the
// velocity at the force's time (YADE's vel + dt/2 accel); torques likewise with
// omega + dt/2 T/I, I = Atoms::inertia (fix nve/sphere's). 0 <= alpha < 1.
// It damps the force present when it runs: define it after every fix that adds
// force (gravity, walls, viscous; a later one is warned about), and before
// enforce2d and freeze, which only zero components.
//
// A grain of a rigid body (fix rigid, rigid/small, multisphere) is damped as
// its body, as YADE damps a clump: not the member's own force and torque, but
// the body's summed force and torque against the body's velocity and angular
// velocity (fixes/rigid_body_set.cpp, with `law` below), the body damped when
// a member is in the group. Damping each member alone would act as dry
// friction on the body (|sum of the members' damping| > |net force| when the
// members' forces nearly cancel): bodies would hang, never in balance.
//
// What it added to each grain's force (3 per atom, this step) is kept when a
// compute asks (compute unbalanced/force measures the force without it, as
// YADE's unbalancedForce() reads forces before the integrator damps them).
#include <vector>

#include "core/engine/fix.h"

namespace sable {

class FixDampingCundall : public Fix {
 public:
  // The law on one component: what damping adds to force f of a grain (or
  // body) whose velocity at the force's time is u.
  static double law(double alpha, double f, double u) {
    return -alpha * f * static_cast<double>((f > 0) - (f < 0)) * static_cast<double>((u > 0) - (u < 0));
  }
  FixDampingCundall(Simulation& s, const Args& a);
  double alpha() const { return alpha_; }
  void init() override;
  void begin(FixHook) override;
  void range(FixHook, const AtomRange& r) override;

  // From the next force pass on, keep the force the damping adds to each grain.
  void keep_added() { keep_ = true; }
  // That force (3 per atom, in Atoms' order) if it was kept on this step for
  // as many atoms as there are now; nullptr otherwise.
  const double* added(std::size_t natoms, long step) const;

 private:
  double alpha_ = 0;
  bool keep_ = false;
  std::vector<double> added_;
  long added_step_ = -1;
};

}  // namespace sable
