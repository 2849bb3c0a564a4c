// Every built-in sub-model (the generated TypeLists of builtin_models.h) as a
// part of laws composed at run time: any combination of them runs, compiled
// or not (contact_models/compiled_laws.txt). A new header joins with nothing
// else to edit.
#include "contact_models/registry.h"

namespace sable {
namespace {

template <class... Ns, class... Ds, class... Ts, class... Rs, class... Cs>
bool register_builtin_parts(TypeList<Ns...>, TypeList<Ds...> ds, TypeList<Ts...>, TypeList<Rs...>, TypeList<Cs...>) {
  (register_normal<Ns>(ds), ...);
  (add_tangential_part<Ts>(), ...);
  (add_rolling_part<Rs>(), ...);
  (add_cohesion_part<Cs>(), ...);
  return true;
}

const bool registered = register_builtin_parts(builtin::Normals{}, builtin::Dampings{}, builtin::Tangentials{},
                                               builtin::Rollings{}, builtin::Cohesions{});

}  // namespace
}  // namespace sable
