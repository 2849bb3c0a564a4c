#pragma once
// rolling_friction off (LIGGGHTS' default): no rolling torque.
#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct RollingOff {
  static constexpr const char* kName = "off";
  static constexpr int kHistory = 0;
  static void history_slots(std::vector<HistorySlot>&) {}
  void settings(ModelSettings&) {}
  void connect(PropertyRequest&) {}
  Vec3 torque(const Contact&, const NormalForce&, double*, const StepContext&) const { return {}; }
};

}  // namespace sable

SABLE_ROLLING_MODEL(sable::RollingOff);
