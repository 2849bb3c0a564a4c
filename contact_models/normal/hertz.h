#pragma once
// model hertz — reproduces LIGGGHTS 3.8 NormalModel<HERTZ> (normal_model_hertz.h):
//   kn = 4/3 Y* sqrt(R* dn),  kt = 8 G* sqrt(R* dn)
//   gamman = -2 sqrt(5/6) beta sqrt(Sn m*),  Sn = 2 Y* sqrt(R* dn)
//   gammat = -2 sqrt(5/6) beta sqrt(St m*),  St = kt   (0 with tangential_damping off)
//   Fn = kn dn - gamman vn   (clipped at 0 with limitForce on)
// Y*, G*, beta = ln e / sqrt(ln^2 e + pi^2) are LIGGGHTS' Yeff, Geff, betaeff.
#include <cmath>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct NormalHertz {
  static constexpr const char* kName = "hertz";
  static constexpr int kHistory = 0;
  static void history_slots(std::vector<HistorySlot>&) {}

  bool tangential_damping = true, limit_force = false;
  const double *Y = nullptr, *G = nullptr, *beta = nullptr;

  void settings(ModelSettings& s) {
    s.on_off("tangential_damping", tangential_damping);
    s.on_off("limitForce", limit_force);
    s.off_only("heating_normal_hertz");
    s.off_only("disableNormalWhenBonded");
    s.off_only("computeDissipatedEnergy");
    s.off_only("computeElasticPotential");
  }
  void connect(PropertyRequest& p) {
    Y = p.pair_table("Yeff");
    G = p.pair_table("Geff");
    beta = p.pair_table("betaeff");
  }

  NormalForce force(const Contact& c, double*, const StepContext&) const {
    constexpr double sqrt_five_sixths = 0.91287092917527685576;
    const double sq = std::sqrt(c.reff * c.deltan);
    const double Sn = 2.0 * Y[c.tp] * sq;
    const double St = 8.0 * G[c.tp] * sq;
    NormalForce n;
    n.kn = 4.0 / 3.0 * Y[c.tp] * sq;
    n.kt = St;
    n.gamman = -2.0 * sqrt_five_sixths * beta[c.tp] * std::sqrt(Sn * c.meff);
    n.gammat = tangential_damping ? -2.0 * sqrt_five_sixths * beta[c.tp] * std::sqrt(St * c.meff) : 0.0;
    n.Fn = n.kn * c.deltan - n.gamman * c.vn;
    if (limit_force && n.Fn < 0.0) n.Fn = 0.0;
    return n;
  }

  // LIGGGHTS' Hertz time (fix check/timestep/gran): 2.87 (m*^2 / (R* Y*^2 v))^(1/5).
  double contact_time(const ContactTimeInput& in) const {
    const double y = Y[in.tp];
    return 2.87 * std::pow(in.meff * in.meff / (in.reff * y * y * in.v), 0.2);
  }
};

}  // namespace sable
