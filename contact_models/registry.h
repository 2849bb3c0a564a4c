#pragma once
// Law registry keyed by sub-model names, one per axis. The build composes
// every built-in normal, damping, tangential, rolling and cohesion model
// (each header under contact_models/<axis>/ that ends with its
// SABLE_<AXIS>_MODEL line; contact_models/models.cmake). An out-of-tree model
// loaded with `plugin load FILE` registers with one line:
//
//   SABLE_GRAN_NORMAL(MyNormal);   // MyNormal x every built-in damping, tangential, rolling, cohesion
//   SABLE_GRAN_MODEL(MyNormal, TangentialHistory, RollingOff);   // one combination (damping liggghts, cohesion off)
//
// A deck then selects it by name: pair_style gran model my/name tangential history.
#include <array>
#include <map>
#include <memory>
#include <string>
#include <type_traits>

#include "contact_models/builtin_models.h"  // generated: every built-in sub-model and its axis' TypeList
#include "contact_models/kernel.h"
#include "core/style_registry.h"

namespace sable {

enum ModelAxis { kNormalAxis, kDampingAxis, kTangentialAxis, kRollingAxis, kCohesionAxis, kAxes };

class GranModelRegistry {
 public:
  using Names = std::array<std::string, kAxes>;
  using Factory = std::unique_ptr<ContactKernel> (*)();
  static std::map<Names, Factory>& table() {
    static std::map<Names, Factory> t;
    return t;
  }
  static bool add(const Names& n, Factory f) {
    table()[n] = f;
    return true;
  }
  static const Factory* find(const Names& n) {
    auto it = table().find(n);
    return it == table().end() ? nullptr : &it->second;
  }
  // Names registered on one axis, comma separated.
  static std::string names(ModelAxis axis);
  static bool has_name(ModelAxis axis, const std::string& name);
};

template <class N, class D, class T, class R, class C>
std::unique_ptr<ContactKernel> make_gran_kernel() {
  return std::make_unique<GranKernel<N, D, T, R, C>>();
}

template <class N, class D, class T, class R, class C>
bool register_gran_model() {
  return GranModelRegistry::add({N::kName, D::kName, T::kName, R::kName, C::kName}, &make_gran_kernel<N, D, T, R, C>);
}

// N and D with every tangential, rolling and cohesion model of the lists.
template <class N, class D, class... Ts, class... Rs, class... Cs>
bool register_product(TypeList<Ts...>, TypeList<Rs...>, TypeList<Cs...>) {
  return ([]<class T>() {
    return ([]<class R>() { return (register_gran_model<N, D, T, R, Cs>() && ...); }.template operator()<Rs>() && ...);
  }.template operator()<Ts>() && ...);
}
template <class N, class D, class Ts, class Rs, class Cs>
bool register_product() {
  return register_product<N, D>(Ts{}, Rs{}, Cs{});
}
// Cohesion models compose with LIGGGHTS' own damping (damping liggghts) only:
// the sable damping models have no cohesive use yet, and each cohesion model
// would add as many laws to compile again (225 laws instead of 405).
template <class D>
using CohesionsFor =
    std::conditional_t<std::is_same_v<D, DampingLiggghts>, builtin::Cohesions, TypeList<CohesionOff>>;
template <class N, class... Ds>
bool register_normal(TypeList<Ds...>) {
  return (register_product<N, Ds, builtin::Tangentials, builtin::Rollings, CohesionsFor<Ds>>() && ...);
}

// The models a deck line selects: model M [damping D] [tangential T]
// [cohesion C] [rolling_friction R] [surface default], with the word index
// of each name for error messages. LIGGGHTS' defaults: tangential off,
// rolling_friction off, cohesion off; damping liggghts (each normal model's own).
struct ModelSelection {
  GranModelRegistry::Names names{"", "liggghts", "off", "off", "off"};
  std::array<std::size_t, kAxes> at{};
  std::size_t next = 0;  // first word after the selection
};
ModelSelection parse_model_selection(const Args& a, std::size_t from);
// The law for a selection, or an error naming the unknown word.
std::unique_ptr<ContactKernel> make_kernel(const ModelSelection& sel, const Args& a);

}  // namespace sable

#define SABLE_GRAN_MODEL(N, T, R)                                                       \
  static const bool SABLE_CAT(sable_gran_model_, __LINE__) =                            \
      ::sable::register_gran_model<N, ::sable::DampingLiggghts, T, R, ::sable::CohesionOff>()
#define SABLE_GRAN_NORMAL(N) \
  static const bool SABLE_CAT(sable_gran_normal_, __LINE__) = ::sable::register_normal<N>(::sable::builtin::Dampings{})
