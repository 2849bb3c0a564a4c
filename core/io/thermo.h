#pragma once
// Thermo output (LIGGGHTS `thermo N`, `thermo_style custom ...`,
// `thermo_modify`): one line of columns every N steps, plus thermo keywords
// for expressions.
#include <string>
#include <vector>

#include "core/input/args.h"

namespace sable {

class Simulation;

class Thermo {
 public:
  explicit Thermo(Simulation& sim);
  long every = 0;  // 0: first and last step of a run only
  void set_style(const Args& a);
  void modify(const Args& a);
  void header();
  void line(long step);
  // Keyword value (step, atoms, ke, time, dt, cpu, box bounds, ...); false if unknown.
  bool keyword(const std::string& name, double& out);
  // Value of any column word: keyword, c_ID[i], f_ID[i], v_name.
  double column(const std::string& word, const Args& where);
  double kinetic_energy() const;
  std::vector<std::string> columns{"step", "atoms", "ke"};
  Args columns_where;

 private:
  Simulation& sim_;
  std::string float_fmt_ = "%.8g", int_fmt_ = "%ld";
  bool norm_ = false;
};

// Parses "c_ID", "c_ID[3]", "f_ID[2]", "v_name" into kind/id/index (index 0 = scalar);
// with `column`, also "f_ID[2][5]" (an array element; column 0 otherwise).
bool parse_reference(const std::string& word, char& kind, std::string& id, int& index, int* column = nullptr);

}  // namespace sable
