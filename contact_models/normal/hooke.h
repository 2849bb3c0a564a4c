#pragma once
// model hooke — reproduces LIGGGHTS 3.8 NormalModel<HOOKE> (normal_model_hooke.h):
//   kn = 16/15 sqrt(R*) Y* (15 m* V^2 / (16 sqrt(R*) Y*))^(1/5),  V = characteristicVelocity
//   kt = kn  (ktToKnUser on: kt = 0.285714286 kn, LIGGGHTS' literal for 2/7)
//   Fn = kn dn - gamman vn   (clipped at 0 with limitForce on)
// Its LIGGGHTS dashpot (restitution e exactly for this linear spring) is
// damping/liggghts.h's `hooke` form.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct NormalHooke : LiggghtsNormal {
  static constexpr const char* kName = "hooke";
  static constexpr LiggghtsDamping kLiggghtsDamping = LiggghtsDamping::hooke;

  bool kt_to_kn = false, viscous = false;
  const double* Y = nullptr;
  double char_vel = 0;

  void settings(ModelSettings& s) {
    switches(s);
    s.on_off("ktToKnUser", kt_to_kn);
    s.off_only("viscous");
    s.off_only("heating_normal_hooke");
    unimplemented(s);
  }
  void connect(PropertyRequest& p) {
    Y = p.pair_table("Yeff");
    p.pair_table("Geff");  // LIGGGHTS connects Geff too, so a deck without poissonsRatio fails there as well
    char_vel = p.scalar("characteristicVelocity");
  }

  double kn_of(double meff, double reff, int tp) const {
    const double sq = std::sqrt(reff);
    return 16.0 / 15.0 * sq * Y[tp] * std::pow(15.0 * meff * char_vel * char_vel / (16.0 * sq * Y[tp]), 0.2);
  }
  double linear_kn(const ContactTimeInput& in) const { return kn_of(in.meff, in.reff, in.tp); }

  NormalForce force(const Contact& c, double*, const StepContext&) const {
    NormalForce n;
    n.kn = kn_of(c.meff, c.reff, c.tp);
    n.kt = kt_to_kn ? n.kn * 0.285714286 : n.kn;
    n.Fel = n.kn * c.deltan;
    return n;
  }

  double contact_time(const ContactTimeInput& in) const { return linear_contact_time(linear_kn(in), in.meff); }
};

}  // namespace sable

SABLE_NORMAL_MODEL(sable::NormalHooke);
