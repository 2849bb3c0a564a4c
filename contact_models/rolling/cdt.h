#pragma once
// rolling_friction cdt — reproduces LIGGGHTS 3.8 RollingModel<ROLLING_CDT> (constant
// directional torque, Ai et al. 2011 model A):
//   Mr = rmu kn dn R* wr / |wr|,  wr = w_i - w_j (wall: cri w_i / r),
// with the component along en removed unless torsionTorque on. kn dn is the
// elastic normal force (no damping). Returned Mr is subtracted from the torque
// on i and added to j. rmu = coefficientRollingFriction.
#include <cmath>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct RollingCdt : NoHistory {
  static constexpr const char* kName = "cdt";

  bool torsion_torque = false;
  const double* rmu = nullptr;
  void settings(ModelSettings& s) { s.on_off("torsionTorque", torsion_torque); }
  void connect(PropertyRequest& p) { rmu = p.pair_table("coefficientRollingFriction"); }

  template <class K>  // Contact or ContactK (2D: spin and torque about z alone)
  Vec3 torque(const K& c, const NormalForce& n, double*, const StepContext&) const {
    const double* w = c.wroll;
    if constexpr (K::kDim == 2) {  // the en component is zero already (en in the plane)
      const double wmag = std::sqrt(w[2] * w[2]);
      if (!(wmag > 0.0)) return {};
      return {0.0, 0.0, w[2] * (rmu[c.tp] * n.kn * c.deltan * c.reff / wmag)};
    }
    const double wmag = std::sqrt(dot(w, w));
    if (!(wmag > 0.0)) return {};
    const double s = rmu[c.tp] * n.kn * c.deltan * c.reff / wmag;
    Vec3 t{w[0] * s, w[1] * s, w[2] * s};
    if (!torsion_torque) {
      const double tn = t.x * c.en[0] + t.y * c.en[1] + t.z * c.en[2];
      t = {t.x - tn * c.en[0], t.y - tn * c.en[1], t.z - tn * c.en[2]};
    }
    return t;
  }
};

}  // namespace sable

SABLE_ROLLING_MODEL(sable::RollingCdt);
