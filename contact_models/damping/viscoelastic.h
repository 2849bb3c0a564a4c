#pragma once
// damping viscoelastic (sable) — dashpots that scale with the contact
// radius sqrt(R* dn), as the Hertz spring does (Brilliantov et al. 1996):
//   gamman = dampingNormal sqrt(R* dn),  gammat = dampingTangential sqrt(R* dn)
// With model hertz this is the Mohr study's law (petit2017 Eqs. 1-2, read with
// consistent units: Fn = sqrt(R* dn) (4/3 Y* dn - gamma_n vn), Ft's dashpot
// gamma_s sqrt(R* dn)). dampingNormal, dampingTangential: peratomtypepair (Pa s).
#include <cmath>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct DampingViscoelastic : NoHistory {
  static constexpr const char* kName = "viscoelastic";
  const double *gn = nullptr, *gt = nullptr;
  void settings(ModelSettings&) {}
  template <class Normal>
  void connect(PropertyRequest& p, Normal&) {
    gn = p.pair_table("dampingNormal");
    gt = p.pair_table("dampingTangential");
  }

  template <class Normal>
  void damp(const Normal&, const Contact& c, NormalForce& n) const {
    const double a = std::sqrt(c.reff * c.deltan);
    n.gamman = gn[c.tp] * a;
    n.gammat = gt[c.tp] * a;
  }
};

}  // namespace sable

SABLE_DAMPING_MODEL(sable::DampingViscoelastic);
