#pragma once
// model hooke/hysteresis — LIGGGHTS 3.8's NormalModel<HOOKE_HYSTERESIS>, a
// Walton-Braun / Luding style elasto-plastic-adhesive linear spring. With kn,
// gamman, gammat of model hooke (normal/hooke.h) and, per type pair,
//   k2Max = kn coefficientMaxElasticStiffness,  kc = kn coefficientAdhesionStiffness,
//   phiF  = coefficientPlasticityDepth,  dLim = k2Max / (k2Max - kn) phiF 2 R*,
// and dMax the largest overlap of this contact (history slot deltaMax):
//   dMax < dLim: k2 = kn + (k2Max - kn) dMax / dLim, unloading line
//                f2 = k2 (dn - dMax) + kn dMax; fHys = min(kn dn, f2) (loading on kn)
//   dMax >= dLim: k2 = k2Max, f2 = k2Max (dn - dLim) + kn dLim; fHys = f2
//   never below the adhesive branch -kc dn; on that branch dMax becomes the
//   maximum whose unloading line meets -kc dn here (solving
//   k2(dMax) (dn - dMax) + kn dMax = -kc dn for dMax):
//   dMax = (dn + sqrt(dn^2 + 4 (kn + kc) dn dLim / (k2Max - kn))) / 2.
//   Fn = fHys - gamman vn,  kt = kn (LIGGGHTS ignores ktToKnUser here).
// Undamped, without adhesion, a collision loading to dMax < dLim rebounds with
// e = sqrt(kn / k2(dMax)) (tests/unit/test_hooke_hysteresis.cpp).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "contact_models/normal/hooke.h"

namespace sable {

struct NormalHookeHysteresis : NormalHooke {
  static constexpr const char* kName = "hooke/hysteresis";
  static constexpr int kHistory = 1;
  static void history_slots(std::vector<HistorySlot>& s) { s.push_back({"deltaMax", false}); }

  const double *k2_ratio = nullptr, *kc_ratio = nullptr, *phi = nullptr;

  void settings(ModelSettings& s) {
    s.on_off("tangential_damping", tangential_damping);
    // LIGGGHTS accepts these (hooke's settings) but this model never reads them: refuse 'on'.
    s.off_only("limitForce");
    s.off_only("ktToKnUser");
    s.off_only("viscous");
    s.off_only("heating_normal_hooke");
    unimplemented(s);
  }
  void connect(PropertyRequest& p) {
    NormalHooke::connect(p);
    k2_ratio = p.pair_table("coefficientMaxElasticStiffness");
    kc_ratio = p.pair_table("coefficientAdhesionStiffness");
    phi = p.pair_table("coefficientPlasticityDepth");
  }

  NormalForce force(const Contact& c, double* h, const StepContext& ctx) const {
    NormalForce n;
    const double kn = kn_of(c.meff, c.reff, c.tp), dn = c.deltan;
    const double k2max = kn * k2_ratio[c.tp], kc = kn * kc_ratio[c.tp];
    const double dlim = (k2max / (k2max - kn)) * phi[c.tp] * 2 * c.reff;
    const double dmax = std::max(h[0], dn);
    const bool plastic = dmax >= dlim;  // beyond dLim: no loading branch, k2 = k2Max
    const double k2 = plastic ? k2max : kn + (k2max - kn) * dmax / dlim;
    const double f2 = plastic ? k2max * (dn - dlim) + kn * dlim : k2 * (dn - dmax) + kn * dmax;
    const double f = plastic ? f2 : std::min(f2, kn * dn);
    const bool adhesive = plastic ? f < -kc * dn : !(f > -kc * dn);
    const double new_max = 0.5 * (dn + std::sqrt(dn * dn + 4 * ((kn + kc) * dn * dlim / (k2max - kn))));
    if (ctx.update) h[0] = adhesive ? new_max : dmax;
    n.kn = kn;
    n.kt = kn;
    n.Fel = adhesive ? -kc * dn : f;
    return n;
  }
  void limit(NormalForce&) const {}

  // The stiffest branch (k2Max) sets the shortest contact time, undamped (not hooke's damped one).
  double linear_kn(const ContactTimeInput&) const = delete;
  double contact_time(const ContactTimeInput& in) const {
    const double kn = kn_of(in.meff, in.reff, in.tp);
    return std::numbers::pi / std::sqrt(kn * k2_ratio[in.tp] / in.meff);
  }
};

}  // namespace sable

SABLE_NORMAL_MODEL(sable::NormalHookeHysteresis);
