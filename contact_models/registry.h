#pragma once
// Law registry keyed by sub-model names, one per axis. Every built-in
// normal, damping, tangential, rolling and cohesion model (each header under
// contact_models/<axis>/ that ends with its SABLE_<AXIS>_MODEL line;
// contact_models/models.cmake) registers its part for laws composed at run
// time (composed.h), so every combination works; the combinations listed in
// contact_models/compiled_laws.txt are also compiled as fast kernels
// (GranKernel). An out-of-tree model loaded with `plugin load FILE` registers
// with one line:
//
//   SABLE_GRAN_NORMAL(MyNormal);   // MyNormal with every built-in damping, tangential, rolling, cohesion (composed)
//   SABLE_GRAN_MODEL(MyNormal, TangentialHistory, RollingOff);   // one compiled combination (damping liggghts,
//                                                                 // cohesion off); its models compose with the others
//
// A deck then selects it by name: pair_style gran model my/name tangential history.
#include <array>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>

#include "contact_models/builtin_models.h"  // generated: every built-in sub-model and its axis' TypeList
#include "contact_models/composed.h"
#include "contact_models/kernel.h"
#include "core/input/style_registry.h"

namespace sable {

class Simulation;

enum ModelAxis { kNormalAxis, kDampingAxis, kTangentialAxis, kRollingAxis, kCohesionAxis, kAxes };

class GranModelRegistry {
 public:
  using Names = std::array<std::string, kAxes>;
  using Factory = std::unique_ptr<ContactKernel> (*)();
  // The compiled laws.
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
  // Every registered sub-model as a part of composed laws, by name (normal: with each damping model).
  struct Parts {
    std::map<std::array<std::string, 2>, std::unique_ptr<NormalPart> (*)()> normal;
    std::map<std::string, std::unique_ptr<TangentialPart> (*)()> tangential;
    std::map<std::string, std::unique_ptr<RollingPart> (*)()> rolling;
    std::map<std::string, std::unique_ptr<CohesionPart> (*)()> cohesion;
  };
  static Parts& parts() {
    static Parts p;
    return p;
  }
  // Names registered on one axis, comma separated.
  static std::string names(ModelAxis axis);
  static bool has_name(ModelAxis axis, const std::string& name);
};

template <class P, class Base>
std::unique_ptr<Base> make_part() {
  return std::make_unique<P>();
}
template <class N, class D>
void add_normal_part() {
  GranModelRegistry::parts().normal[{N::kName, D::kName}] = &make_part<NormalPartOf<N, D>, NormalPart>;
}
template <class T>
void add_tangential_part() {
  GranModelRegistry::parts().tangential[T::kName] = &make_part<TangentialPartOf<T>, TangentialPart>;
}
template <class R>
void add_rolling_part() {
  GranModelRegistry::parts().rolling[R::kName] = &make_part<RollingPartOf<R>, RollingPart>;
}
template <class C>
void add_cohesion_part() {
  GranModelRegistry::parts().cohesion[C::kName] = &make_part<CohesionPartOf<C>, CohesionPart>;
}

template <class N, class D, class T, class R, class C>
std::unique_ptr<ContactKernel> make_gran_kernel() {
  return std::make_unique<GranKernel<N, D, T, R, C>>();
}

// One compiled law; its sub-models also join the composed laws.
template <class N, class D, class T, class R, class C>
bool register_gran_model() {
  add_normal_part<N, D>();
  add_tangential_part<T>();
  add_rolling_part<R>();
  add_cohesion_part<C>();
  return GranModelRegistry::add({N::kName, D::kName, T::kName, R::kName, C::kName}, &make_gran_kernel<N, D, T, R, C>);
}

// N with every damping model of the list, composed at run time.
template <class N, class... Ds>
bool register_normal(TypeList<Ds...>) {
  (add_normal_part<N, Ds>(), ...);
  return true;
}

// A name as a template argument: the law sources that models.cmake generates
// from contact_models/compiled_laws.txt name their models, not their types.
template <std::size_t K>
struct LawName {
  char s[K];
  constexpr LawName(const char (&a)[K]) {
    for (std::size_t i = 0; i < K; ++i) s[i] = a[i];
  }
  constexpr std::string_view view() const { return {s, K - 1}; }
};
// The model of a TypeList whose kName is `name` (void: none).
template <LawName name, class T, class... Ts>
constexpr auto named(TypeList<T, Ts...>) {
  if constexpr (std::string_view(T::kName) == name.view())
    return std::type_identity<T>{};
  else if constexpr (sizeof...(Ts) > 0)
    return named<name>(TypeList<Ts...>{});
  else
    return std::type_identity<void>{};
}
template <LawName name, class List>
using Named = typename decltype(named<name>(List{}))::type;

// One line of contact_models/compiled_laws.txt: the built-in models of these names, compiled.
template <LawName n, LawName d, LawName t, LawName r, LawName c>
bool register_listed_law() {
  using N = Named<n, builtin::Normals>;
  using D = Named<d, builtin::Dampings>;
  using T = Named<t, builtin::Tangentials>;
  using R = Named<r, builtin::Rollings>;
  using C = Named<c, builtin::Cohesions>;
  static_assert(!std::is_void_v<N>, "compiled_laws.txt: no normal model of this name (contact_models/normal/)");
  static_assert(!std::is_void_v<D>, "compiled_laws.txt: no damping model of this name (contact_models/damping/)");
  static_assert(!std::is_void_v<T>, "compiled_laws.txt: no tangential model of this name (contact_models/tangential/)");
  static_assert(!std::is_void_v<R>, "compiled_laws.txt: no rolling model of this name (contact_models/rolling/)");
  static_assert(!std::is_void_v<C>, "compiled_laws.txt: no cohesion model of this name (contact_models/cohesion/)");
  return register_gran_model<N, D, T, R, C>();
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
// The law for a selection (compiled if listed, else composed at run time,
// which `sim` is told once), or an error naming the unknown word.
// SABLE_COMPOSED_LAWS=1 in the environment composes every law (to compare the paths).
std::unique_ptr<ContactKernel> make_kernel(const ModelSelection& sel, const Args& a, Simulation& sim);

}  // namespace sable

#define SABLE_GRAN_MODEL(N, T, R)                                                       \
  static const bool SABLE_CAT(sable_gran_model_, __COUNTER__) =                            \
      ::sable::register_gran_model<N, ::sable::DampingLiggghts, T, R, ::sable::CohesionOff>()
#define SABLE_GRAN_NORMAL(N) \
  static const bool SABLE_CAT(sable_gran_normal_, __COUNTER__) = ::sable::register_normal<N>(::sable::builtin::Dampings{})
