#pragma once
// model linear/kneib (sable addition; no LIGGGHTS model of this name) — the
// linear spring-dashpot of the cavity paper (Kneib et al. 2017, Appendix B),
// as YADE's FrictViscoMat + Ip2_FrictViscoMat_FrictViscoMat_FrictViscoPhys +
// Law2_ScGeom_FrictViscoPhys_CundallStrackVisco compute it:
//   kn = 2 Ei Ej ri rj / (Ei ri + Ej rj)  (= E 2 ri rj / (ri + rj) for one material),
//        a wall taking the grain's radius (kn = E r), as YADE's Ig2_Wall_Sphere does
//   kt = kn (nu_i + nu_j) / 2             (nu = poissonsRatio, here the ratio ks/kn)
//   Fn = kn dn - gamman vn                 (limitForce on clips at 0)
//   its dashpot (damping liggghts, the default): damping restitution's
//   gamman = 2 |beta| sqrt(m* kn) (restitution e exactly), gammat = 0
// E = youngsModulus, e = coefficientRestitution; the tangential spring is the
// tangential model's (`tangential history`: Coulomb-capped incremental spring).
#include <cmath>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct NormalLinearKneib : NoHistory {
  static constexpr const char* kName = "linear/kneib";
  static constexpr LiggghtsDamping kLiggghtsDamping = LiggghtsDamping::restitution;

  bool limit_force = false;
  // Per type pair (index c.tp): E of the i type, E of the j type, (nu_i + nu_j) / 2.
  std::vector<double> Ei, Ej, ratio;

  void settings(ModelSettings& s) {
    s.on_off("limitForce", limit_force);
    s.off_only("tangential_damping");
  }
  void connect(PropertyRequest& p) {
    const double* E = p.type_vector("youngsModulus");
    const double* nu = p.type_vector("poissonsRatio");
    const int s = p.stride();
    Ei.assign(s * s, 0.0);
    Ej.assign(s * s, 0.0);
    ratio.assign(s * s, 0.0);
    for (int i = 1; i < s; ++i)
      for (int j = 1; j < s; ++j) {
        Ei[i * s + j] = E[i];
        Ej[i * s + j] = E[j];
        ratio[i * s + j] = 0.5 * (nu[i] + nu[j]);
      }
  }

  NormalForce force(const Contact& c, double*, const StepContext&) const {
    NormalForce n;
    const double rj = c.is_wall ? c.radi : c.radj;
    const double ei = Ei[c.tp] * c.radi, ej = Ej[c.tp] * rj;
    n.kn = 2.0 * ei * ej / (ei + ej);
    n.kt = ratio[c.tp] * n.kn;
    n.Fel = n.kn * c.deltan;
    return n;
  }
  void limit(NormalForce& n) const {
    if (limit_force && n.Fn < 0.0) n.Fn = 0.0;
  }

  // kn of two grains of radius 2 reff.
  double linear_kn(const ContactTimeInput& in) const {
    return 2.0 * Ei[in.tp] * Ej[in.tp] / (Ei[in.tp] + Ej[in.tp]) * 2.0 * in.reff;
  }
  double contact_time(const ContactTimeInput& in) const { return linear_contact_time(linear_kn(in), in.meff); }
};

}  // namespace sable

SABLE_NORMAL_MODEL(sable::NormalLinearKneib);
