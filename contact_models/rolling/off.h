#pragma once
// rolling_friction off (LIGGGHTS' default): no rolling torque.
#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct RollingOff : NoHistory {
  static constexpr const char* kName = "off";
  void settings(ModelSettings&) {}
  void connect(PropertyRequest&) {}
  Vec3 torque(const Contact&, const NormalForce&, double*, const StepContext&) const { return {}; }
};

}  // namespace sable

SABLE_ROLLING_MODEL(sable::RollingOff);
