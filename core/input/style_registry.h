#pragma once
// Name -> factory tables. Each style registers itself with one macro line
// next to its class (SABLE_FIX("wall/gran", FixWallGran)); nothing central
// lists them, and a plugin .so registers the same way when loaded.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/input/plugin_abi.h"  // every source that registers carries the plugin tag

namespace sable {

class Simulation;
class Args;

template <class Product, class... CtorArgs>
class Registry {
 public:
  using Factory = std::function<Product(CtorArgs...)>;
  static std::map<std::string, Factory>& table() {
    static std::map<std::string, Factory> t;
    return t;
  }
  static bool add(const std::string& name, Factory f) {
    table()[name] = std::move(f);
    return true;
  }
  static const Factory* find(const std::string& name) {
    auto it = table().find(name);
    return it == table().end() ? nullptr : &it->second;
  }
  static std::string names() {
    std::string s;
    for (auto& [k, v] : table()) s += (s.empty() ? "" : ", ") + k;
    return s;
  }
};

class Fix;
class Compute;
class Region;
class Dump;
using FixRegistry = Registry<std::unique_ptr<Fix>, Simulation&, const Args&>;
using ComputeRegistry = Registry<std::unique_ptr<Compute>, Simulation&, const Args&>;
using RegionRegistry = Registry<std::unique_ptr<Region>, Simulation&, const Args&>;
using DumpRegistry = Registry<std::unique_ptr<Dump>, Simulation&, const Args&>;
// Deck commands that are not styles (create_box, run, set, ...).
using CommandRegistry = Registry<void, Simulation&, const Args&>;

}  // namespace sable

#define SABLE_CAT2(a, b) a##b
#define SABLE_CAT(a, b) SABLE_CAT2(a, b)
#define SABLE_REGISTER_STYLE(Reg, name, Class)                                                    \
  static const bool SABLE_CAT(sable_registered_, __COUNTER__) = ::sable::Reg::add(                 \
      name, [](::sable::Simulation& s, const ::sable::Args& a) { return std::make_unique<Class>(s, a); })
#define SABLE_FIX(name, Class) SABLE_REGISTER_STYLE(FixRegistry, name, Class)
#define SABLE_COMPUTE(name, Class) SABLE_REGISTER_STYLE(ComputeRegistry, name, Class)
#define SABLE_REGION(name, Class) SABLE_REGISTER_STYLE(RegionRegistry, name, Class)
#define SABLE_DUMP(name, Class) SABLE_REGISTER_STYLE(DumpRegistry, name, Class)
#define SABLE_COMMAND(name, fn) \
  static const bool SABLE_CAT(sable_registered_, __COUNTER__) = ::sable::CommandRegistry::add(name, fn)

namespace sable {
class Pair;
using PairRegistry = Registry<std::unique_ptr<Pair>, Simulation&, const Args&>;
}  // namespace sable
#define SABLE_PAIR(name, Class) SABLE_REGISTER_STYLE(PairRegistry, name, Class)
