#include "core/engine/global_property.h"

#include "core/engine/fix.h"
#include "core/engine/simulation.h"

namespace sable {

namespace {
unsigned long g_generation = 0;
}

GlobalProperty::GlobalProperty() { ++g_generation; }
GlobalProperty::~GlobalProperty() { ++g_generation; }
unsigned long GlobalProperty::generation() { return g_generation; }

const GlobalProperty* GlobalProperty::find(const Simulation& sim, const std::string& name) {
  for (auto& f : sim.fixes)
    if (auto* p = dynamic_cast<const GlobalProperty*>(f.get()); p && p->name == name) return p;
  return nullptr;
}

}  // namespace sable
