#pragma once
// model hertz/stiffness — reproduces LIGGGHTS 3.8 NormalModel<HERTZ_STIFFNESS>:
//   with s = sqrt(R* dn):  kn = s kn[ij],  kt = s kt[ij]
//   Fn = kn dn - gamman vn (limitForce clips at 0)
// Its LIGGGHTS dashpot (s m* gamman[ij], no absolute_damping) is
// damping/liggghts.h's `hertz_stiffness` form.
#include <cmath>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct NormalHertzStiffness : LiggghtsNormal {
  static constexpr const char* kName = "hertz/stiffness";
  static constexpr LiggghtsDamping kLiggghtsDamping = LiggghtsDamping::hertz_stiffness;

  const double *kn_ = nullptr, *kt_ = nullptr;

  void settings(ModelSettings& s) { switches(s); }
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

  // kn[ij] sqrt(R* dn) dn is Hertz with Y* = 3/4 kn[ij]: 2.87 (m*^2 / (R* Y*^2 v))^(1/5), damping ignored.
  double contact_time(const ContactTimeInput& in) const {
    const double y = 0.75 * kn_[in.tp];
    return 2.87 * std::pow(in.meff * in.meff / (in.reff * y * y * in.v), 0.2);
  }
};

}  // namespace sable

SABLE_NORMAL_MODEL(sable::NormalHertzStiffness);
