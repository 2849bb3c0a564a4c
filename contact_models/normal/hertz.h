#pragma once
// model hertz — reproduces LIGGGHTS 3.8 NormalModel<HERTZ> (normal_model_hertz.h):
//   kn = 4/3 Y* sqrt(R* dn),  kt = 8 G* sqrt(R* dn)
//   gamman = -2 sqrt(5/6) beta sqrt(Sn m*),  Sn = 2 Y* sqrt(R* dn)
//   gammat = -2 sqrt(5/6) beta sqrt(St m*),  St = kt   (0 with tangential_damping off)
//   Fn = kn dn - gamman vn   (clipped at 0 with limitForce on)
// Y*, G*, beta = ln e / sqrt(ln^2 e + pi^2) are LIGGGHTS' Yeff, Geff, betaeff.
#include <cmath>
#include <limits>
#include <vector>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct NormalHertz {
  static constexpr const char* kName = "hertz";
  static constexpr int kHistory = 0;
  static void history_slots(std::vector<HistorySlot>&) {}

  bool tangential_damping = true, limit_force = false;
  const double* Y = nullptr;

  void settings(ModelSettings& s) {
    s.on_off("tangential_damping", tangential_damping);
    s.on_off("limitForce", limit_force);
    s.off_only("heating_normal_hertz");
    s.off_only("disableNormalWhenBonded");
    s.off_only("computeDissipatedEnergy");
    s.off_only("computeElasticPotential");
  }
  // Per type pair, once: everything in the formulas above that does not depend
  // on the contact, so a contact costs two square roots (sqrt(R* dn) and
  // sqrt(sqrt(R* dn) m*)) instead of three, and no branch (the loop vectorises):
  //   sqrt(Sn m*) = sqrt(2 Y*) sqrt(sqrt(R* dn) m*),  sqrt(St m*) = sqrt(8 G*) sqrt(sqrt(R* dn) m*).
  // Equal to LIGGGHTS' evaluation to round-off (a few ulp).
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
  // LIGGGHTS' damping of this model (damping liggghts, the default).
  void connect_damping(PropertyRequest& p) {
    const double* G = p.pair_table("Geff");
    const double* beta = p.pair_table("betaeff");
    constexpr double sqrt_five_sixths = 0.91287092917527685576;
    const int n = p.stride() * p.stride();
    gn_c.assign(n, 0.0), gt_c.assign(n, 0.0);
    for (int t = 0; t < n; ++t) {
      gn_c[t] = -2.0 * sqrt_five_sixths * beta[t] * std::sqrt(2.0 * Y[t]);
      gt_c[t] = tangential_damping ? -2.0 * sqrt_five_sixths * beta[t] * std::sqrt(8.0 * G[t]) : 0.0;
    }
  }
  void damping(const Contact& c, NormalForce& n) const {
    const double sm = std::sqrt(n.s * c.meff);
    n.gamman = gn_c[c.tp] * sm;
    n.gammat = gt_c[c.tp] * sm;
  }
  void limit(NormalForce& n) const { n.Fn = n.Fn < fn_floor ? fn_floor : n.Fn; }  // limitForce: no attraction

  // LIGGGHTS' Hertz time (fix check/timestep/gran): 2.87 (m*^2 / (R* Y*^2 v))^(1/5).
  double contact_time(const ContactTimeInput& in) const {
    const double y = Y[in.tp];
    return 2.87 * std::pow(in.meff * in.meff / (in.reff * y * y * in.v), 0.2);
  }

 private:
  std::vector<double> kn_c, kt_c, gn_c, gt_c;  // per type pair: 4/3 Y*, 8 G*, damping prefactors
  double fn_floor = 0.0;                        // 0 with limitForce on, else -inf
};

}  // namespace sable

SABLE_NORMAL_MODEL(sable::NormalHertz);
