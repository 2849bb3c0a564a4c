#pragma once
// model hooke/stiffness — reproduces LIGGGHTS 3.8 NormalModel<HOOKE_STIFFNESS>:
//   kn, kt from property/global kn, kt (peratomtypepair)
//   gamman = m* gamman[ij], gammat = m* gammat[ij]; with absolute_damping on
//   gamman = gamman_abs[ij], gammat = gammat_abs[ij] (no m*)
//   gammat = 0 with tangential_damping off;  Fn = kn dn - gamman vn (limitForce clips at 0)
#include <algorithm>
#include <cmath>
#include <numbers>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct NormalHookeStiffness {
  static constexpr const char* kName = "hooke/stiffness";
  static constexpr int kHistory = 0;
  static void history_slots(std::vector<HistorySlot>&) {}

  bool tangential_damping = true, limit_force = false, absolute_damping = false;
  const double *kn_ = nullptr, *kt_ = nullptr, *gn_ = nullptr, *gt_ = nullptr;

  void settings(ModelSettings& s) {
    s.on_off("tangential_damping", tangential_damping);
    s.on_off("absolute_damping", absolute_damping);
    s.on_off("limitForce", limit_force);
    s.off_only("disableNormalWhenBonded");
    s.off_only("computeDissipatedEnergy");
    s.off_only("computeElasticPotential");
  }
  void connect(PropertyRequest& p) {
    kn_ = p.pair_table("kn");
    kt_ = p.pair_table("kt");
  }

  NormalForce force(const Contact& c, double*, const StepContext&) const {
    NormalForce n;
    n.kn = kn_[c.tp];
    n.kt = kt_[c.tp];
    n.Fel = n.kn * c.deltan;
    return n;
  }
  // LIGGGHTS' damping of this model (damping liggghts, the default).
  void connect_damping(PropertyRequest& p) {
    gn_ = p.pair_table(absolute_damping ? "gamman_abs" : "gamman");
    gt_ = p.pair_table(absolute_damping ? "gammat_abs" : "gammat");
  }
  void damping(const Contact& c, NormalForce& n) const {
    const double scale = absolute_damping ? 1.0 : c.meff;
    n.gamman = scale * gn_[c.tp];
    n.gammat = tangential_damping ? scale * gt_[c.tp] : 0.0;
  }
  void limit(NormalForce& n) const {
    if (limit_force && n.Fn < 0.0) n.Fn = 0.0;
  }

  // Damped linear oscillator: pi / sqrt(kn/m* - (gamman / 2m*)^2).
  double contact_time(const ContactTimeInput& in) const {
    const double kn = kn_[in.tp];
    const double g = gn_ ? (absolute_damping ? 1.0 : in.meff) * gn_[in.tp] : 0.0;  // another damping model: undamped
    const double w2 = kn / in.meff - g * g / (4.0 * in.meff * in.meff);
    return std::numbers::pi / std::sqrt(std::max(w2, 1e-300));
  }
};

}  // namespace sable

SABLE_NORMAL_MODEL(sable::NormalHookeStiffness);
