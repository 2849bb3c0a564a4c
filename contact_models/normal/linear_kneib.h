#pragma once
// model linear/kneib (sable addition; no LIGGGHTS model of this name) — the
// linear spring-dashpot of the cavity paper (Kneib et al. 2017, Appendix B),
// as YADE's FrictViscoMat + Ip2_FrictViscoMat_FrictViscoMat_FrictViscoPhys +
// Law2_ScGeom_FrictViscoPhys_CundallStrackVisco compute it:
//   kn = 2 Ei Ej ri rj / (Ei ri + Ej rj)  (= E 2 ri rj / (ri + rj) for one material),
//        a wall taking the grain's radius (kn = E r), as YADE's Ig2_Wall_Sphere does
//   kt = kn (nu_i + nu_j) / 2             (nu = poissonsRatio, here the ratio ks/kn)
//   gamman = 2 |beta| sqrt(m* kn), beta = ln e / sqrt(ln^2 e + pi^2): restitution e exactly
//   gammat = 0                             (no tangential dashpot)
//   Fn = kn dn - gamman vn                 (limitForce on clips at 0)
// E = youngsModulus, e = coefficientRestitution; the tangential spring is the
// tangential model's (`tangential history`: Coulomb-capped incremental spring).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct NormalLinearKneib {
  static constexpr const char* kName = "linear/kneib";
  static constexpr int kHistory = 0;
  static void history_slots(std::vector<HistorySlot>&) {}

  bool limit_force = false;
  // Per type pair (index c.tp): E of the i type, E of the j type, (nu_i + nu_j) / 2, 2 |beta|.
  std::vector<double> Ei, Ej, ratio, two_beta;

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
  // Its own dashpot (damping liggghts, the default): the restitution dashpot, no tangential one.
  void connect_damping(PropertyRequest& p) {
    const double* beta = p.pair_table("betaeff");
    const int n = p.stride() * p.stride();
    two_beta.assign(n, 0.0);
    for (int t = 0; t < n; ++t) two_beta[t] = 2.0 * std::fabs(beta[t]);
  }
  void damping(const Contact& c, NormalForce& n) const {
    n.gamman = two_beta[c.tp] * std::sqrt(c.meff * n.kn);
    n.gammat = 0.0;
  }
  void limit(NormalForce& n) const {
    if (limit_force && n.Fn < 0.0) n.Fn = 0.0;
  }

  // Damped linear oscillator, pi / sqrt(kn/m* - (gamman / 2m*)^2), with kn of two grains of radius reff*2.
  double contact_time(const ContactTimeInput& in) const {
    const double kn = 2.0 * Ei[in.tp] * Ej[in.tp] / (Ei[in.tp] + Ej[in.tp]) * 2.0 * in.reff;
    const double b = two_beta.empty() ? 0.0 : 0.5 * two_beta[in.tp];
    return std::numbers::pi / std::sqrt(kn / in.meff * std::max(1.0 - b * b, 1e-300));
  }
};

}  // namespace sable

SABLE_NORMAL_MODEL(sable::NormalLinearKneib);
