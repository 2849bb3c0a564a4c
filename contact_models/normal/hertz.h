#pragma once
// model hertz — reproduces LIGGGHTS 3.8 NormalModel<HERTZ> (normal_model_hertz.h):
//   kn = 4/3 Y* sqrt(R* dn),  kt = 8 G* sqrt(R* dn)
//   Fn = kn dn - gamman vn   (clipped at 0 with limitForce on)
// Y*, G* are LIGGGHTS' Yeff, Geff. Its LIGGGHTS dashpot (gamman, gammat from
// sqrt(R* dn)) is damping/liggghts.h's `hertz` form.
#include <cmath>
#include <limits>
#include <vector>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct NormalHertz : LiggghtsNormal {
  static constexpr const char* kName = "hertz";
  static constexpr LiggghtsDamping kLiggghtsDamping = LiggghtsDamping::hertz;

  const double* Y = nullptr;

  void settings(ModelSettings& s) {
    switches(s);
    s.off_only("heating_normal_hertz");
    unimplemented(s);
  }
  // Per type pair, once: the factors of kn and kt that do not depend on the contact.
  void connect(PropertyRequest& p) {
    Y = p.pair_table("Yeff");
    const double* G = p.pair_table("Geff");
    const int n = p.stride() * p.stride();
    kn_c.assign(n, 0.0), kt_c.assign(n, 0.0);
    for (int t = 0; t < n; ++t) {
      kn_c[t] = 4.0 / 3.0 * Y[t];
      kt_c[t] = 8.0 * G[t];
    }
    fn_floor = limit_force ? 0.0 : -std::numeric_limits<double>::infinity();
  }

  NormalForce force(const Contact& c, double*, const StepContext&) const {
    NormalForce n;
    n.s = std::sqrt(c.reff * c.deltan);
    n.kn = kn_c[c.tp] * n.s;
    n.kt = kt_c[c.tp] * n.s;
    n.Fel = n.kn * c.deltan;
    return n;
  }
  // limitForce: LiggghtsNormal::limit without its branch (the hot path of the common law).
  void limit(NormalForce& n) const { n.Fn = n.Fn < fn_floor ? fn_floor : n.Fn; }

  // LIGGGHTS' Hertz time (fix check/timestep/gran): 2.87 (m*^2 / (R* Y*^2 v))^(1/5).
  double contact_time(const ContactTimeInput& in) const {
    const double y = Y[in.tp];
    return 2.87 * std::pow(in.meff * in.meff / (in.reff * y * y * in.v), 0.2);
  }

 private:
  std::vector<double> kn_c, kt_c;  // per type pair: 4/3 Y*, 8 G*
  double fn_floor = 0.0;           // 0 with limitForce on, else -inf
};

}  // namespace sable

SABLE_NORMAL_MODEL(sable::NormalHertz);
