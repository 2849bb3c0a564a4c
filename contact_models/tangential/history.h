#pragma once
// tangential history — reproduces LIGGGHTS 3.8 TangentialModel<TANGENTIAL_HISTORY>
// (tangential_model_history.h), i.e. the LAMMPS gran/hooke/history spring:
//   1. shear += vtr dt, then the normal component is removed
//      (shear -= (shear . en) en): the spring is projected, not rotated with
//      its length kept, onto the current tangent plane;
//   2. Ft = -kt shear;
//   3. Coulomb cap |Ft| <= mu |Fn| with Fn the damped (possibly limited) normal force;
//      at slip Ft is scaled to mu |Fn| and shear = -Ft / kt (no tangential damping);
//      otherwise Ft -= gammat vtr.
// History changes only when ctx.update (not during setup or per-contact output).
// Slots shearx, sheary, shearz change sign when the pair is seen as (j, i).
#include <cmath>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct TangentialHistory {
  static constexpr const char* kName = "history";
  static constexpr int kHistory = 3;
  static void history_slots(std::vector<HistorySlot>& s) {
    s.push_back({"shearx", true});
    s.push_back({"sheary", true});
    s.push_back({"shearz", true});
  }

  const double* mu = nullptr;
  void settings(ModelSettings& s) {
    s.off_only("heating_tangential_history");
    s.off_only("heating_tracking");
  }
  void connect(PropertyRequest& p) { mu = p.pair_table("coefficientFriction"); }

  // Written with selects instead of branches so the kernel's contact loop
  // vectorises; with ctx.update a compile-time constant there, they fold away.
  // At slip the spring shrinks by the same ratio as the force
  // (shear = -Ft/kt = ratio shear, LIGGGHTS' expression to round-off).
  template <class K>  // Contact or ContactK (2D: the z terms, exact zeros there, are left out)
  Vec3 force(const K& c, const NormalForce& n, double* shear, const StepContext& ctx) const {
    constexpr bool k3 = K::kDim == 3;
    const double* en = c.en;
    double s0 = shear[0], s1 = shear[1], s2 = k3 ? shear[2] : 0.0;
    {
      const double a0 = s0 + c.vtr[0] * ctx.dt, a1 = s1 + c.vtr[1] * ctx.dt, a2 = k3 ? s2 + c.vtr[2] * ctx.dt : 0.0;
      const double rsht = k3 ? a0 * en[0] + a1 * en[1] + a2 * en[2] : a0 * en[0] + a1 * en[1];
      s0 = ctx.update ? a0 - rsht * en[0] : s0;
      s1 = ctx.update ? a1 - rsht * en[1] : s1;
      if constexpr (k3) s2 = ctx.update ? a2 - rsht * en[2] : s2;
    }
    const double kt = n.kt;
    const double shrmag = std::sqrt(k3 ? s0 * s0 + s1 * s1 + s2 * s2 : s0 * s0 + s1 * s1);
    const double ft_shear = kt * shrmag, ft_friction = mu[c.tp] * std::fabs(n.Fn);
    const bool slip = ft_shear > ft_friction;
    // slip with shrmag = 0 cannot happen for mu >= 0; LIGGGHTS zeroes the force then, as ratio 0 does
    const double ratio = shrmag != 0.0 ? ft_friction / ft_shear : 0.0;
    const double fac = slip ? ratio : 1.0, gam = slip ? 0.0 : n.gammat;  // at slip: no damping
    Vec3 f;
    f.x = -kt * s0 * fac - gam * c.vtr[0];
    f.y = -kt * s1 * fac - gam * c.vtr[1];
    f.z = k3 ? -kt * s2 * fac - gam * c.vtr[2] : 0.0;
    const double keep = ctx.update ? fac : 1.0;
    shear[0] = s0 * keep;
    shear[1] = s1 * keep;
    if constexpr (k3) shear[2] = s2 * keep;
    return f;
  }
};

}  // namespace sable

SABLE_TANGENTIAL_MODEL(sable::TangentialHistory);
