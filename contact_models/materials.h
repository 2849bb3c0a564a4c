#pragma once
// Per-type-pair coefficient tables derived once from `fix property/global`
// values, shared by the pair style and every wall of a simulation (as
// LIGGGHTS' PropertyRegistry: Yeff, Geff, betaeff, ... are built once and
// connected to every model that names them). Sub-models ask for tables in
// connect() through a PropertyRequest, whose errors name the model, the
// missing property, the `fix ... property/global` line that would define it
// and the deck line of the pair_style / fix wall/gran that needs it.
//
// Tables are flat: table[itype * (ntypes + 1) + jtype], types 1..ntypes.
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace sable {

class Args;
class Simulation;
class GlobalProperty;

class Materials {
 public:
  // The shared tables of `sim` (rebuilt when property fixes or ntypes changed).
  static std::shared_ptr<Materials> of(Simulation& sim);
  explicit Materials(Simulation& sim);

  int ntypes() const { return ntypes_; }
  int stride() const { return ntypes_ + 1; }
  bool has(const std::string& property) const;

  // Each returns a table that lives as long as this object; `who` is
  // "model hertz" etc., `line` the style's deck line (for errors).
  const double* pair_table(const std::string& name, const std::string& who, const Args& line);
  const double* type_vector(const std::string& name, const std::string& who, const Args& line);
  double scalar(const std::string& name, const std::string& who, const Args& line);

 private:
  Simulation& sim_;
  int ntypes_ = 0;
  unsigned long generation_ = 0;
  std::map<std::string, std::vector<double>> tables_;
  std::map<std::string, double> scalars_;

  const GlobalProperty& require(const std::string& name, const char* style, const std::string& who,
                                   const Args& line) const;
  std::vector<double> raw_pair(const std::string& name, const std::string& who, const Args& line) const;
  std::vector<double> raw_type(const std::string& name, const std::string& who, const Args& line) const;
  void check_range(const std::string& name, const std::vector<double>& t) const;
  std::string example_line(const std::string& name, const char* style) const;
};

// What one sub-model's connect() talks to: the shared tables plus who is asking.
class PropertyRequest {
 public:
  PropertyRequest(Materials& m, const Args& line, std::string who) : m_(m), line_(line), who_(std::move(who)) {}
  // Raw peratomtypepair properties (coefficientFriction, kn, ...) or derived
  // ones: Yeff, Geff, betaeff, coeffRestLog (LIGGGHTS' names).
  const double* pair_table(const std::string& name) { return m_.pair_table(name, who_, line_); }
  const double* type_vector(const std::string& name) { return m_.type_vector(name, who_, line_); }
  double scalar(const std::string& name) { return m_.scalar(name, who_, line_); }
  bool has(const std::string& name) const { return m_.has(name); }
  int stride() const { return m_.stride(); }
  const std::string& who() const { return who_; }
  void set_who(std::string w) { who_ = std::move(w); }
  const Args& line() const { return line_; }

 private:
  Materials& m_;
  const Args& line_;
  std::string who_;
};

}  // namespace sable
