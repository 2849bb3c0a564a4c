#pragma once
// fix ID group property/global NAME style [nCols] values...   (LIGGGHTS fix_property.txt)
//   style: scalar | vector | atomtype | peratomtype | matrix | atomtypepair | peratomtypepair
// Holds named global values (material properties) that contact models read at
// init through core/engine/global_property.h. atomtypepair matrices must be
// square and symmetric, as in LIGGGHTS. f_ID / f_ID[i] give the scalar / vector.
#include <string>
#include <vector>

#include "core/engine/fix.h"
#include "core/engine/global_property.h"

namespace sable {

class FixPropertyGlobal : public Fix, public GlobalProperty {
 public:
  FixPropertyGlobal(Simulation& sim, const Args& args);
  void export_yade(YadeScript&) const override {}  // read by the materials the script writes

  double compute_scalar() override { return values.empty() ? 0.0 : values[0]; }
  double compute_vector(int i) override;  // 1-based
};

}  // namespace sable
