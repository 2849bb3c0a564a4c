#pragma once
// A compute's numeric argument that is a number or v_name (an equal-style
// variable read at each invocation), e.g. a slice bound that follows a piston.
#include <string>

#include "core/input/args.h"
#include "core/engine/simulation.h"
#include "core/input/variable.h"

namespace sable {

struct BoundArg {
  double value = 0;
  std::string var;  // empty: a number
  std::size_t at = 0;

  // Word i of a: a number, or v_name of an equal-style variable (checked now).
  static BoundArg parse(const Simulation& s, const Args& a, std::size_t i, const std::string& what) {
    BoundArg b;
    b.at = i;
    const std::string& w = a.word(i, what);
    if (w.rfind("v_", 0) == 0 && w.size() > 2) b.var = w.substr(2);
    else b.value = a.num(i, what);
    if (!b.var.empty() && !s.variables->is_equal_style(b.var))
      a.fail(i, "an equal-style variable (v_" + b.var + " is not one)");
    return b;
  }
  // The value now; `a` names the command in an error.
  double eval(Simulation& s, const Args& a) const {
    if (var.empty()) return value;
    double v = 0;
    if (!s.variables->numeric(var, v)) a.fail(at, "an equal-style variable (v_" + var + ")");
    return v;
  }
};

}  // namespace sable
