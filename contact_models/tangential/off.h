#pragma once
// tangential off — LIGGGHTS' default when no 'tangential' is given (TANGENTIAL_OFF):
// frictionless contacts, no coefficientFriction needed.
#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct TangentialOff : NoHistory {
  static constexpr const char* kName = "off";
  void settings(ModelSettings&) {}
  void connect(PropertyRequest&) {}
  Vec3 force(const Contact&, const NormalForce&, double*, const StepContext&) const { return {}; }
};

}  // namespace sable

SABLE_TANGENTIAL_MODEL(sable::TangentialOff);
