// An out-of-tree contact model, built as a shared library and loaded by a deck:
//
//   plugin load /path/to/example_contact_plugin.so
//   fix d all property/global dampingPetit peratomtypepair 1 0.5
//   pair_style gran model hertz/petit tangential history
//
// The normal law of Petit et al. 2017 (Mohr paper, Eq. 1), read with
// consistent units as a Hertz spring and a dashpot that both scale with the
// contact radius sqrt(R* dn):
//
//   Fn = sqrt(R* dn) (kn dn - gamma vn),   kn = 4/3 Y*   (Y* = LIGGGHTS' Yeff)
//
// (the paper writes sqrt(xi_n) R_eff (k_n xi_n + gamma_n dxi_n/dt)). This is the
// viscoelastic Hertz model of Brilliantov et al. 1996, whose restitution is
// known analytically (Schwager & Poschel 1998), so tests/unit/test_plugin.cpp
// can check a head-on collision. The tangential stiffness is Mindlin's
// 8 G* sqrt(R* dn) (the paper's Eq. 2 with k_s = 8G/(2-nu) for equal grains) and
// the tangential dashpot gamma sqrt(R* dn), as the paper uses gamma_n = gamma_s.
// gamma is the per-type-pair property dampingPetit (Pa s).
//
// SABLE_GRAN_NORMAL registers the model with every built-in damping,
// tangential, rolling and cohesion model, composed at run time, so all of
// `tangential off|no_history|history` and `rolling_friction off|cdt|epsd2`
// work with it; SABLE_GRAN_MODEL compiles the combination a deck runs most as
// a fast kernel (the others say on the screen that they run composed).
#include <cmath>

#include "contact_models/registry.h"

namespace {

using namespace sable;

struct NormalHertzPetit {
  static constexpr const char* kName = "hertz/petit";
  static constexpr int kHistory = 0;
  static void history_slots(std::vector<HistorySlot>&) {}
  static constexpr LiggghtsDamping kLiggghtsDamping = LiggghtsDamping::own;  // damping() below

  const double *Y = nullptr, *G = nullptr, *gamma = nullptr;

  void settings(ModelSettings&) {}
  void connect(PropertyRequest& p) {
    Y = p.pair_table("Yeff");
    G = p.pair_table("Geff");
  }
  void connect_damping(PropertyRequest& p) { gamma = p.pair_table("dampingPetit"); }

  NormalForce force(const Contact& c, double*, const StepContext&) const {
    NormalForce n;
    n.s = std::sqrt(c.reff * c.deltan);  // contact radius
    n.kn = 4.0 / 3.0 * Y[c.tp] * n.s;
    n.kt = 8.0 * G[c.tp] * n.s;
    n.Fel = n.kn * c.deltan;
    return n;
  }
  // Its own dashpot (what `damping liggghts`, the default, applies).
  void damping(const Contact& c, NormalForce& n) const {
    n.gamman = gamma[c.tp] * n.s;
    n.gammat = gamma[c.tp] * n.s;
  }
  void limit(NormalForce&) const {}

  // Undamped Hertz duration, as for model hertz.
  double contact_time(const ContactTimeInput& in) const {
    const double y = Y[in.tp];
    return 2.87 * std::pow(in.meff * in.meff / (in.reff * y * y * in.v), 0.2);
  }
};

SABLE_GRAN_NORMAL(NormalHertzPetit);
SABLE_GRAN_MODEL(NormalHertzPetit, TangentialHistory, RollingOff);

}  // namespace
