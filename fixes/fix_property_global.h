#pragma once
// fix ID group property/global NAME style [nCols] values...   (LIGGGHTS fix_property.txt)
//   style: scalar | vector | atomtype | peratomtype | matrix | atomtypepair | peratomtypepair
// Holds named global values (material properties) that contact models read at
// init through contact_models/materials.h. atomtypepair matrices must be
// square and symmetric, as in LIGGGHTS. f_ID / f_ID[i] give the scalar / vector.
#include <string>
#include <vector>

#include "core/fix.h"

namespace sable {

class FixPropertyGlobal : public Fix {
 public:
  enum class Kind { Scalar, Vector, Matrix };
  FixPropertyGlobal(Simulation& sim, const Args& args);
  ~FixPropertyGlobal() override;

  std::string name;         // the variable name, e.g. youngsModulus
  std::string style_word;   // as written (peratomtype, atomtypepair, ...)
  Kind kind = Kind::Scalar;
  bool symmetric = false;   // atomtypepair / peratomtypepair
  int ncols = 1;            // matrix columns
  std::vector<double> values;

  double compute_scalar() override { return values.empty() ? 0.0 : values[0]; }
  double compute_vector(int i) override;  // 1-based
  std::size_t rows() const { return kind == Kind::Matrix ? values.size() / ncols : values.size(); }
  double at(int row, int col) const { return values[row * ncols + col]; }

  // The fix defining NAME, or nullptr.
  static FixPropertyGlobal* find(const Simulation& sim, const std::string& name);
  // Bumped whenever a property/global fix is created or destroyed, so derived
  // material tables know when to rebuild.
  static unsigned long generation();
};

}  // namespace sable
