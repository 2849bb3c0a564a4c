#pragma once
// damping liggghts (the default) — each normal model's own LIGGGHTS 3.8
// damping (its damping() member: hertz's viscoelastic gamman = -2 sqrt(5/6)
// beta sqrt(Sn m*), hooke's restitution-exact linear dashpot, the stiffness
// models' gamman/gammat tables), so a LIGGGHTS deck means what it meant there.
#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

struct DampingLiggghts {
  static constexpr const char* kName = "liggghts";
  static constexpr int kHistory = 0;
  static void history_slots(std::vector<HistorySlot>&) {}
  void settings(ModelSettings&) {}
  template <class Normal>
  void connect(PropertyRequest& p, Normal& normal) {
    p.set_who(std::string("model ") + Normal::kName);  // LIGGGHTS' damping is the normal model's
    normal.connect_damping(p);
  }

  template <class Normal>
  void damp(const Normal& normal, const Contact& c, NormalForce& n) const {
    normal.damping(c, n);
  }
};

}  // namespace sable

SABLE_DAMPING_MODEL(sable::DampingLiggghts);
