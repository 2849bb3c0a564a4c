#pragma once
// model hertz/stiffness — reproduces LIGGGHTS 3.8 NormalModel<HERTZ_STIFFNESS>:
//   with s = sqrt(R* dn):  kn = s kn[ij],  kt = s kt[ij],
//   gamman = s m* gamman[ij],  gammat = s m* gammat[ij] (0 with tangential_damping off)
//   Fn = kn dn - gamman vn (limitForce clips at 0). LIGGGHTS has no absolute_damping here.
#include <cmath>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct NormalHertzStiffness {
  static constexpr const char* kName = "hertz/stiffness";
  static constexpr int kHistory = 0;
  static void history_slots(std::vector<HistorySlot>&) {}

  bool tangential_damping = true, limit_force = false;
  const double *kn_ = nullptr, *kt_ = nullptr, *gn_ = nullptr, *gt_ = nullptr;

  void settings(ModelSettings& s) {
    s.on_off("tangential_damping", tangential_damping);
    s.on_off("limitForce", limit_force);
  }
  void connect(PropertyRequest& p) {
    kn_ = p.pair_table("kn");
    kt_ = p.pair_table("kt");
  }

  NormalForce force(const Contact& c, double*, const StepContext&) const {
    NormalForce n;
    n.s = std::sqrt(c.reff * c.deltan);
    n.kn = n.s * kn_[c.tp];
    n.kt = n.s * kt_[c.tp];
    n.Fel = n.kn * c.deltan;
    return n;
  }
  // LIGGGHTS' damping of this model (damping liggghts, the default).
  void connect_damping(PropertyRequest& p) {
    gn_ = p.pair_table("gamman");
    gt_ = p.pair_table("gammat");
  }
  void damping(const Contact& c, NormalForce& n) const {
    n.gamman = n.s * c.meff * gn_[c.tp];
    n.gammat = tangential_damping ? n.s * c.meff * gt_[c.tp] : 0.0;
  }
  void limit(NormalForce& n) const {
    if (limit_force && n.Fn < 0.0) n.Fn = 0.0;
  }

  // kn[ij] sqrt(R* dn) dn is Hertz with Y* = 3/4 kn[ij]: 2.87 (m*^2 / (R* Y*^2 v))^(1/5), damping ignored.
  double contact_time(const ContactTimeInput& in) const {
    const double y = 0.75 * kn_[in.tp];
    return 2.87 * std::pow(in.meff * in.meff / (in.reff * y * y * in.v), 0.2);
  }
};

}  // namespace sable

SABLE_NORMAL_MODEL(sable::NormalHertzStiffness);
