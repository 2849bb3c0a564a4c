#include "core/engine/contact_source.h"

#include "core/engine/simulation.h"

namespace sable {

std::vector<ContactSource*> contact_sources(Simulation& sim) {
  std::vector<ContactSource*> out;
  if (auto* p = dynamic_cast<ContactSource*>(sim.pair.get())) out.push_back(p);
  for (auto& f : sim.fixes)
    if (auto* s = dynamic_cast<ContactSource*>(f.get())) out.push_back(s);
  return out;
}

ContactSource* pair_contacts(Simulation& sim) { return dynamic_cast<ContactSource*>(sim.pair.get()); }

ContactSource* contact_source_of_fix(Simulation& sim, const std::string& id) {
  return dynamic_cast<ContactSource*>(sim.find_fix(id));
}

}  // namespace sable
