#pragma once
// cohesion off — LIGGGHTS' default: no attraction. kActive = false removes the
// axis from the compiled law (not even an added zero).
#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct CohesionOff : NoHistory {
  static constexpr const char* kName = "off";
  static constexpr bool kActive = false;
  void settings(ModelSettings&) {}
  void connect(PropertyRequest&) {}
  double force(const Contact&, const NormalForce&, double*, const StepContext&) const { return 0.0; }
  bool reduces_tangential() const { return false; }
};

}  // namespace sable

SABLE_COHESION_MODEL(sable::CohesionOff);
