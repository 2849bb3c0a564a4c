#pragma once
// tangential no_history — reproduces LIGGGHTS 3.8 TangentialModel<TANGENTIAL_NO_HISTORY>:
// viscous friction Ft = -min(mu |Fn|, gammat |vtr|) vtr / |vtr|, no spring, no history.
#include <algorithm>
#include <cmath>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct TangentialNoHistory : NoHistory {
  static constexpr const char* kName = "no_history";

  const double* mu = nullptr;
  void settings(ModelSettings&) {}
  void connect(PropertyRequest& p) { mu = p.pair_table("coefficientFriction"); }

  template <class K>  // Contact or ContactK (2D: z left out)
  Vec3 force(const K& c, const NormalForce& n, double*, const StepContext&) const {
    const double vrel = std::sqrt(dot_d<K::kDim>(c.vtr, c.vtr));
    if (vrel == 0.0) return {};
    const double ft = std::min(mu[c.tp] * std::fabs(n.Fn), n.gammat * vrel) / vrel;
    return {-ft * c.vtr[0], -ft * c.vtr[1], K::kDim == 3 ? -ft * c.vtr[2] : 0.0};
  }
};

}  // namespace sable

SABLE_TANGENTIAL_MODEL(sable::TangentialNoHistory);
