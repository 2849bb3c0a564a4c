#pragma once
// Deck variables (LAMMPS `variable NAME style args`): index, loop, string,
// equal, atom. Equal/atom formulas are parsed once and evaluated on demand.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/input/args.h"

namespace sable {

class Simulation;
class Expression;

class Variables {
 public:
  explicit Variables(Simulation& sim);
  ~Variables();
  void define(const Args& a);                       // the `variable` command
  void define_index(const std::string& name, const std::vector<std::string>& values);  // -var
  bool next(const std::string& name, const Args& where);  // false when exhausted (then deleted)
  bool exists(const std::string& name) const { return vars_.count(name) > 0; }
  // ${name}: current string, or an equal formula evaluated and printed.
  std::string string_value(const std::string& name, const Args& where);
  // v_name as a number (equal style, or a numeric index/string value).
  bool numeric(const std::string& name, double& out);
  // atom-style variable: one value per atom.
  bool atom_values(const std::string& name, std::vector<double>& out);
  bool is_atom_style(const std::string& name) const;
  bool is_equal_style(const std::string& name) const {
    auto it = vars_.find(name);
    return it != vars_.end() && it->second.style == "equal";
  }
  // Evaluate a formula now; errors name the deck line.
  double evaluate(const std::string& expr, const Args& where);
  // Loop, index and string variables' values, and (for `jump` loops) whether any changed.
  std::string fingerprint() const;

 private:
  struct Var {
    std::string style;
    std::vector<std::string> values;
    std::size_t which = 0;
    std::shared_ptr<Expression> expr;  // equal/atom
    long first = 0, count = 0;         // loop: values first .. first+count-1, made when asked
    int pad = 0;                       // loop: zero-padded width (0 = no padding)
    DeckLocation where;                // definition, named when evaluating it fails later
  };
  static std::string current(const Var& v);
  static std::size_t size(const Var& v) { return v.style == "loop" ? static_cast<std::size_t>(v.count) : v.values.size(); }
  void check_names(const Args& a, const Expression& e, bool atom_style);
  Simulation& sim_;
  std::map<std::string, Var> vars_;
  int depth_ = 0;  // recursion guard for self-referencing formulas
};

}  // namespace sable
