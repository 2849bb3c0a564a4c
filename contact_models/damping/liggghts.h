#pragma once
// damping liggghts (the default) — the dashpot each normal model has in
// LIGGGHTS 3.8, so a LIGGGHTS deck means what it meant there. The normal model
// names its form (kLiggghtsDamping) and exports what the form reads: kn and
// s = sqrt(R* dn) in NormalForce, its tangential_damping and absolute_damping
// keywords, and linear_kn (a linear spring's stiffness, for the contact time).
//   hertz            gamman = -2 sqrt(5/6) beta sqrt(Sn m*),  Sn = 2 Y* s
//                    gammat = -2 sqrt(5/6) beta sqrt(St m*),  St = 8 G* s   (normal_model_hertz.h)
//   hooke            gamman = sqrt(4 m* kn / (1 + (pi / ln e)^2)),  gammat = gamman  (normal_model_hooke.h:
//                    restitution e exactly on the linear spring)
//   stiffness        gamman = m* gamman[ij],  gammat = m* gammat[ij]; absolute_damping on:
//                    gamman_abs[ij], gammat_abs[ij]  (normal_model_hooke_stiffness.h)
//   hertz_stiffness  gamman = s m* gamman[ij],  gammat = s m* gammat[ij]  (normal_model_hertz_stiffness.h)
//   restitution      damping restitution's dashpot (linear/kneib: YADE's FrictViscoPhys)
//   own              the normal model's damping() (a plugin's model may bring its dashpot)
// gammat = 0 with tangential_damping off; beta = ln e / sqrt(ln^2 e + pi^2) (betaeff).
// A linear spring's contact time is the damped oscillator's half period.
#include <cmath>
#include <numbers>
#include <string>

#include "contact_models/contact.h"
#include "contact_models/damping/restitution.h"
#include "contact_models/materials.h"

namespace sable {

struct DampingLiggghts : NoHistory {
  static constexpr const char* kName = "liggghts";
  void settings(ModelSettings&) {}

  template <class Normal>
  void connect(PropertyRequest& p, Normal& normal) {
    using enum LiggghtsDamping;
    p.set_who(std::string("model ") + Normal::kName);  // in LIGGGHTS this dashpot is the normal model's
    constexpr LiggghtsDamping form = Normal::kLiggghtsDamping;
    if constexpr (form == hertz) connect_hertz(p, normal.tangential_damping);
    if constexpr (form == hooke) log_e_ = p.pair_table("coeffRestLog");
    if constexpr (form == stiffness) {
      gn_ = p.pair_table(normal.absolute_damping ? "gamman_abs" : "gamman");
      gt_ = p.pair_table(normal.absolute_damping ? "gammat_abs" : "gammat");
    }
    if constexpr (form == hertz_stiffness) gn_ = p.pair_table("gamman"), gt_ = p.pair_table("gammat");
    if constexpr (form == restitution) restitution_.connect(p);
    if constexpr (form == own) normal.connect_damping(p);
  }

  template <class Normal>
  void damp(const Normal& normal, const Contact& c, NormalForce& n) const {
    using enum LiggghtsDamping;
    constexpr LiggghtsDamping form = Normal::kLiggghtsDamping;
    if constexpr (form == hertz) {
      const double sm = std::sqrt(n.s * c.meff);
      n.gamman = hertz_n_[c.tp] * sm;
      n.gammat = hertz_t_[c.tp] * sm;
    }
    if constexpr (form == hooke) {
      n.gamman = hooke_gamman(c.meff, n.kn, c.tp);
      n.gammat = normal.tangential_damping ? n.gamman : 0.0;
    }
    if constexpr (form == stiffness) {
      const double scale = normal.absolute_damping ? 1.0 : c.meff;
      n.gamman = scale * gn_[c.tp];
      n.gammat = normal.tangential_damping ? scale * gt_[c.tp] : 0.0;
    }
    if constexpr (form == hertz_stiffness) {
      n.gamman = n.s * c.meff * gn_[c.tp];
      n.gammat = normal.tangential_damping ? n.s * c.meff * gt_[c.tp] : 0.0;
    }
    if constexpr (form == restitution) restitution_.damp(c, n);
    if constexpr (form == own) normal.damping(c, n);
  }

  template <class Normal>
  double contact_time(const Normal& normal, const ContactTimeInput& in) const {
    using enum LiggghtsDamping;
    constexpr LiggghtsDamping form = Normal::kLiggghtsDamping;
    if constexpr (requires { normal.linear_kn(in); }) {
      const double kn = normal.linear_kn(in);
      if constexpr (form == hooke) return linear_contact_time(kn, in.meff, hooke_gamman(in.meff, kn, in.tp));
      if constexpr (form == stiffness)
        return linear_contact_time(kn, in.meff, (normal.absolute_damping ? 1.0 : in.meff) * gn_[in.tp]);
      if constexpr (form == restitution) return restitution_.contact_time(kn, in);
    }
    return normal.contact_time(in);
  }

 private:
  std::vector<double> hertz_n_, hertz_t_;  // hertz: per type pair -2 sqrt(5/6) beta sqrt(2 Y*), ... sqrt(8 G*)
  const double* log_e_ = nullptr;          // hooke: ln e per type pair
  const double *gn_ = nullptr, *gt_ = nullptr;  // the stiffness models' gamman, gammat tables
  RestitutionDashpot restitution_;

  // Per type pair, once: so that a contact costs one square root, sqrt(s m*), and
  // no branch (the loop vectorises): sqrt(Sn m*) = sqrt(2 Y*) sqrt(s m*),
  // sqrt(St m*) = sqrt(8 G*) sqrt(s m*). Equal to LIGGGHTS' evaluation to a few ulp.
  void connect_hertz(PropertyRequest& p, bool tangential_damping) {
    const double* Y = p.pair_table("Yeff");
    const double* G = p.pair_table("Geff");
    const double* beta = p.pair_table("betaeff");
    constexpr double sqrt_five_sixths = 0.91287092917527685576;
    const int n = p.stride() * p.stride();
    hertz_n_.assign(n, 0.0), hertz_t_.assign(n, 0.0);
    for (int t = 0; t < n; ++t) {
      hertz_n_[t] = -2.0 * sqrt_five_sixths * beta[t] * std::sqrt(2.0 * Y[t]);
      hertz_t_[t] = tangential_damping ? -2.0 * sqrt_five_sixths * beta[t] * std::sqrt(8.0 * G[t]) : 0.0;
    }
  }
  double hooke_gamman(double meff, double kn, int tp) const {
    const double q = std::numbers::pi / log_e_[tp];  // e = 1: ln e = 0, q = inf, gamman = 0 (undamped)
    return std::sqrt(4.0 * meff * kn / (1.0 + q * q));
  }
};

}  // namespace sable

SABLE_DAMPING_MODEL(sable::DampingLiggghts);
