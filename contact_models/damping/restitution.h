#pragma once
// damping restitution (sable; LAMMPS' granular `damping coeff_restitution`
// for a linear spring) — the dashpot that gives restitution e to a linear
// spring of stiffness kn, evaluated with the normal model's current kn:
//   gamman = 2 |beta| sqrt(m* kn),  beta = ln e / sqrt(ln^2 e + pi^2),  gammat = 0
// e = coefficientRestitution. The cavity study's law (kneib2017 Appendix B:
// c_n from e = 0.5, no tangential dashpot; YADE's FrictViscoPhys) with
// model hooke/stiffness, and model linear/kneib's own dashpot in LIGGGHTS'
// sense (damping/liggghts.h). With a Hertz spring it is the same formula on
// the current tangent stiffness, and e is then only approximate.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

// The formula, shared with damping liggghts' `restitution` form.
struct RestitutionDashpot {
  std::vector<double> two_beta;  // per type pair: 2 |beta|

  void connect(PropertyRequest& p) {
    const double* beta = p.pair_table("betaeff");  // ln e / sqrt(ln^2 e + pi^2), LIGGGHTS' betaeff
    const int n = p.stride() * p.stride();
    two_beta.assign(n, 0.0);
    for (int t = 0; t < n; ++t) two_beta[t] = 2.0 * std::fabs(beta[t]);
  }
  void damp(const Contact& c, NormalForce& n) const {
    n.gamman = two_beta[c.tp] * std::sqrt(c.meff * n.kn);
    n.gammat = 0.0;
  }
  // The damped half period on a linear spring kn: pi / sqrt(kn/m* (1 - beta^2)).
  double contact_time(double kn, const ContactTimeInput& in) const {
    const double b = 0.5 * two_beta[in.tp];
    return std::numbers::pi / std::sqrt(kn / in.meff * std::max(1.0 - b * b, 1e-300));
  }
};

struct DampingRestitution : NoHistory {
  static constexpr const char* kName = "restitution";
  void settings(ModelSettings&) {}
  template <class Normal>
  void connect(PropertyRequest& p, Normal&) {
    dashpot_.connect(p);
  }
  template <class Normal>
  void damp(const Normal&, const Contact& c, NormalForce& n) const {
    dashpot_.damp(c, n);
  }

 private:
  RestitutionDashpot dashpot_;
};

}  // namespace sable

SABLE_DAMPING_MODEL(sable::DampingRestitution);
