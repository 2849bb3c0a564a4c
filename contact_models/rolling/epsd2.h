#pragma once
// rolling_friction epsd2 — reproduces LIGGGHTS 3.8 RollingModel<ROLLING_EPSD2>
// (elastic-plastic spring, Iwashita & Oda; no rolling dashpot):
//   wr_t = wr without its en component (unless torsionTorque on)
//   Mr = Mr_old + kr wr_t dt,  kr = kt R*^2   (kt from the normal model)
//   |Mr| <= rmu R* |Fn|  (Fn the damped normal force)
// Mr is stored (slots r_torquex_old.. , sign flips for (j, i)) only when ctx.update.
#include <cmath>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct RollingEpsd2 {
  static constexpr const char* kName = "epsd2";
  static constexpr int kHistory = 3;
  static void history_slots(std::vector<HistorySlot>& s) {
    s.push_back({"r_torquex_old", true});
    s.push_back({"r_torquey_old", true});
    s.push_back({"r_torquez_old", true});
  }

  bool torsion_torque = false;
  const double* rmu = nullptr;
  void settings(ModelSettings& s) { s.on_off("torsionTorque", torsion_torque); }
  void connect(PropertyRequest& p) { rmu = p.pair_table("coefficientRollingFriction"); }

  template <class K>  // Contact or ContactK (2D: spin and torque about z alone)
  Vec3 torque(const K& c, const NormalForce& n, double* h, const StepContext& ctx) const {
    const double kr = n.kt * c.reff * c.reff;
    const double tmax = std::fabs(n.Fn) * c.reff * rmu[c.tp];
    if constexpr (K::kDim == 2) {  // wroll is along z, normal to en: nothing to remove
      double tz = h[2] + c.wroll[2] * ctx.dt * kr;
      const double tmag = std::sqrt(tz * tz);
      if (tmag > tmax) tz = tz * (tmax / tmag);
      if (ctx.update) h[2] = tz;
      return {0.0, 0.0, tz};
    }
    double w[3] = {c.wroll[0], c.wroll[1], c.wroll[2]};
    if (!torsion_torque) {
      const double wn = dot(w, c.en);
      for (int k = 0; k < 3; ++k) w[k] -= wn * c.en[k];
    }
    Vec3 t{h[0] + w[0] * ctx.dt * kr, h[1] + w[1] * ctx.dt * kr, h[2] + w[2] * ctx.dt * kr};
    const double tmag = std::sqrt(t.x * t.x + t.y * t.y + t.z * t.z);
    if (tmag > tmax) {
      const double f = tmax / tmag;
      t = {t.x * f, t.y * f, t.z * f};
    }
    if (ctx.update) {
      h[0] = t.x;
      h[1] = t.y;
      h[2] = t.z;
    }
    return t;
  }
};

}  // namespace sable

SABLE_ROLLING_MODEL(sable::RollingEpsd2);
