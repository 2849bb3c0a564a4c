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
// History is written only when ctx.update (not during setup or per-contact output).
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

  Vec3 force(const Contact& c, const NormalForce& n, double* shear, const StepContext& ctx) const {
    const double* en = c.en;
    double s0 = shear[0], s1 = shear[1], s2 = shear[2];
    if (ctx.update) {
      s0 += c.vtr[0] * ctx.dt;
      s1 += c.vtr[1] * ctx.dt;
      s2 += c.vtr[2] * ctx.dt;
      const double rsht = s0 * en[0] + s1 * en[1] + s2 * en[2];
      s0 -= rsht * en[0];
      s1 -= rsht * en[1];
      s2 -= rsht * en[2];
    }
    const double kt = n.kt;
    Vec3 f{-kt * s0, -kt * s1, -kt * s2};
    const double shrmag = std::sqrt(s0 * s0 + s1 * s1 + s2 * s2);
    const double ft_shear = kt * shrmag, ft_friction = mu[c.tp] * std::fabs(n.Fn);
    if (ft_shear > ft_friction) {
      if (shrmag != 0.0) {
        const double ratio = ft_friction / ft_shear;
        f = {f.x * ratio, f.y * ratio, f.z * ratio};
        if (ctx.update) {
          s0 = -f.x / kt;
          s1 = -f.y / kt;
          s2 = -f.z / kt;
        }
      } else {
        f = {0, 0, 0};
      }
    } else {
      f.x -= n.gammat * c.vtr[0];
      f.y -= n.gammat * c.vtr[1];
      f.z -= n.gammat * c.vtr[2];
    }
    if (ctx.update) {
      shear[0] = s0;
      shear[1] = s1;
      shear[2] = s2;
    }
    return f;
  }
};

}  // namespace sable
