// fix ID group property/atom NAME scalar|vector restart comm_ghost comm_rev v1 [v2 ...]
// A named per-atom value (LIGGGHTS 3.8 fix_property.txt): every grain, inserted
// ones too, starts with the default value(s); `set ... property/atom ID v` sets
// it, dumps and compute reduce read it as f_ID (scalar; f_ID[0] as LIGGGHTS
// writes it too) or f_ID[k] (vector, k = 1..n). Stored as the Atoms column
// f_ID, so it follows the grains through sorting and restarts.
// Differences: sable finds the property by its fix ID (LIGGGHTS by NAME; the
// two are the same in every LIGGGHTS example); the three yes/no flags concern
// several processes and are only checked; a vector's defaults must be equal.
#include "fixes/fix_property_atom.h"

#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

FixPropertyAtom::FixPropertyAtom(Simulation& s, const Args& a) : Fix(s, a) {
  a.word(4, "the property's name");
  const std::string& kind = a.word(5, "scalar or vector");
  if (kind != "scalar" && kind != "vector") a.fail(5, "scalar or vector");
  for (std::size_t i = 6; i < 9; ++i) a.yes_no(i, "yes or no");
  const double v0 = a.num(9, "the default value");
  std::size_t n = 1;
  if (kind == "vector") {
    for (n = 1; 9 + n < a.size(); ++n)
      if (a.num(9 + n, "a default value") != v0)
        a.fail(9 + n, "the same default as the first component (sable gives a vector one default)");
  } else if (a.size() > 10) {
    a.fail(10, "nothing more (a scalar property has one default value)");
  }
  s.atoms.add_column("f_" + id, static_cast<int>(n), v0);
}

SABLE_FIX("property/atom", FixPropertyAtom);

}  // namespace sable
