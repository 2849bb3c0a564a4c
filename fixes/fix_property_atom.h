#pragma once
// fix ID group property/atom NAME scalar|vector ... (fixes/fix_property_atom.cpp): a named
// per-atom value stored as the Atoms column f_ID; other styles recognise it by its class.
#include "core/engine/fix.h"

namespace sable {

class FixPropertyAtom : public Fix {
 public:
  FixPropertyAtom(Simulation& s, const Args& a);
};

}  // namespace sable
