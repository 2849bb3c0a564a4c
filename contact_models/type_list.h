#pragma once
// A compile-time list of types (the sub-models of one axis).
namespace sable {
template <class... Ts>
struct TypeList {};
}  // namespace sable
