#pragma once
// Kernel registry keyed by sub-model names, and the one-line registration
// macros. The engine registers every built-in combination (4 normal x 3
// tangential x 3 rolling = 36 kernels, contact_models/builtin_*.cpp); an
// out-of-tree model loaded with `plugin load FILE` registers the same way:
//
//   SABLE_GRAN_NORMAL(MyNormal);              // MyNormal x every built-in tangential x rolling
//   SABLE_GRAN_MODEL(MyNormal, TangentialHistory, RollingOff);   // one combination
//
// A deck then selects it by name: pair_style gran model my/name tangential history.
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "contact_models/kernel.h"
#include "contact_models/normal/hertz.h"
#include "contact_models/normal/hertz_stiffness.h"
#include "contact_models/normal/hooke.h"
#include "contact_models/normal/hooke_stiffness.h"
#include "contact_models/rolling/cdt.h"
#include "contact_models/rolling/epsd2.h"
#include "contact_models/rolling/off.h"
#include "contact_models/tangential/history.h"
#include "contact_models/tangential/no_history.h"
#include "contact_models/tangential/off.h"
#include "core/style_registry.h"

namespace sable {

class GranModelRegistry {
 public:
  using Factory = std::unique_ptr<ContactKernel> (*)();
  static std::map<std::string, Factory>& table() {
    static std::map<std::string, Factory> t;
    return t;
  }
  static std::string key(const std::string& n, const std::string& t, const std::string& r) {
    return n + " " + t + " " + r;
  }
  static bool add(const char* n, const char* t, const char* r, Factory f) {
    table()[key(n, t, r)] = f;
    return true;
  }
  static const Factory* find(const std::string& n, const std::string& t, const std::string& r) {
    auto it = table().find(key(n, t, r));
    return it == table().end() ? nullptr : &it->second;
  }
  // Names registered for one axis (0 normal, 1 tangential, 2 rolling), comma separated.
  static std::string names(int axis);
  static bool has_name(int axis, const std::string& name);
};

template <class N, class T, class R>
std::unique_ptr<ContactKernel> make_gran_kernel() {
  return std::make_unique<GranKernel<N, T, R>>();
}

template <class N, class T, class R>
bool register_gran_model() {
  return GranModelRegistry::add(N::kName, T::kName, R::kName, &make_gran_kernel<N, T, R>);
}

template <class N, class T>
bool register_gran_rolling() {
  return register_gran_model<N, T, RollingOff>() && register_gran_model<N, T, RollingCdt>() &&
         register_gran_model<N, T, RollingEpsd2>();
}

template <class N>
bool register_gran_normal() {
  return register_gran_rolling<N, TangentialOff>() && register_gran_rolling<N, TangentialNoHistory>() &&
         register_gran_rolling<N, TangentialHistory>();
}

// The models a deck line selects: model M [tangential T] [cohesion off]
// [rolling_friction R] [surface default], with the word index of each name
// for error messages. LIGGGHTS' defaults: tangential off, rolling_friction off.
struct ModelSelection {
  std::string normal, tangential = "off", rolling = "off";
  std::size_t normal_at = 0, tangential_at = 0, rolling_at = 0;
  std::size_t next = 0;  // first word after the selection
};
ModelSelection parse_model_selection(const Args& a, std::size_t from);
// The kernel for a selection, or an error naming the unknown word.
std::unique_ptr<ContactKernel> make_kernel(const ModelSelection& sel, const Args& a);

}  // namespace sable

#define SABLE_GRAN_MODEL(N, T, R) \
  static const bool SABLE_CAT(sable_gran_model_, __LINE__) = ::sable::register_gran_model<N, T, R>()
#define SABLE_GRAN_NORMAL(N) \
  static const bool SABLE_CAT(sable_gran_normal_, __LINE__) = ::sable::register_gran_normal<N>()
