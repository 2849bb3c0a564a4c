#pragma once
// A named global value set (LIGGGHTS `fix property/global`: youngsModulus,
// coefficientFriction, ...): what the contact laws' material tables read.
// The fix that parses it (fixes/fix_property_global.cpp) is one; readers
// find it by name here without knowing that fix.
#include <string>
#include <vector>

#include "core/input/args.h"

namespace sable {

class Simulation;

class GlobalProperty {
 public:
  enum class Kind { Scalar, Vector, Matrix };
  GlobalProperty();
  virtual ~GlobalProperty();
  GlobalProperty(const GlobalProperty&) = delete;
  GlobalProperty& operator=(const GlobalProperty&) = delete;

  std::string name;         // the variable name, e.g. youngsModulus
  std::string style_word;   // as written (peratomtype, atomtypepair, ...)
  Kind kind = Kind::Scalar;
  bool symmetric = false;   // atomtypepair / peratomtypepair
  int ncols = 1;            // matrix columns
  std::vector<double> values;
  const Args* line = nullptr;  // the defining deck line, for messages

  std::size_t rows() const { return kind == Kind::Matrix ? values.size() / ncols : values.size(); }
  double at(int row, int col) const { return values[row * ncols + col]; }

  // The property NAME the deck defines, or nullptr.
  static const GlobalProperty* find(const Simulation& sim, const std::string& name);
  // Bumped whenever a property is created or destroyed, so derived tables know when to rebuild.
  static unsigned long generation();
};

}  // namespace sable
