#pragma once
// Styles of LIGGGHTS 2.x that LIGGGHTS 3 removed (LIGGGHTS 3.8 stops at them
// too: "Invalid pair style", "Invalid fix style"), as old decks such as the
// public tutorial contactModels/in.oldModels still use them. An unknown style
// name is looked up here so the error says what replaced it.
#include <string>

namespace sable {

// What replaced style `name` of `kind` ("pair_style" or "fix"), or "" if it is not a removed style.
std::string removed_style_hint(const std::string& kind, const std::string& name);

}  // namespace sable
