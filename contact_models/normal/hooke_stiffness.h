#pragma once
// model hooke/stiffness — reproduces LIGGGHTS 3.8 NormalModel<HOOKE_STIFFNESS>:
//   kn, kt from property/global kn, kt (peratomtypepair)
//   Fn = kn dn - gamman vn (limitForce clips at 0)
// Its LIGGGHTS dashpot (gamman, gammat tables; absolute_damping) is
// damping/liggghts.h's `stiffness` form.

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct NormalHookeStiffness : LiggghtsNormal {
  static constexpr const char* kName = "hooke/stiffness";
  static constexpr LiggghtsDamping kLiggghtsDamping = LiggghtsDamping::stiffness;

  bool absolute_damping = false;
  const double *kn_ = nullptr, *kt_ = nullptr;

  void settings(ModelSettings& s) {
    switches(s);
    s.on_off("absolute_damping", absolute_damping);
    unimplemented(s);
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

  double linear_kn(const ContactTimeInput& in) const { return kn_[in.tp]; }
  double contact_time(const ContactTimeInput& in) const { return linear_contact_time(linear_kn(in), in.meff); }
};

}  // namespace sable

SABLE_NORMAL_MODEL(sable::NormalHookeStiffness);
