#pragma once
// What fix addforce, setforce and aveforce share (LAMMPS syntax): three force
// components, each a number, v_name or NULL, the `region ID` option, and who is
// acted on (GroupForceFix, their base).
// Variables are looked up at init (so they may be defined after the fix) and
// evaluated once a step, serially, before the per-atom pass reads them.
#include <cmath>
#include <string>
#include <vector>

#include "core/engine/simulation.h"
#include "core/input/variable.h"

namespace sable {

class YadeScript;
// sable --export-yade of fix aveforce (ave) and setforce (fixes/group_force_yade.cpp).
void export_yade_set_forces(YadeScript& s, const Fix& f, bool ave);

class ForceComponents {
 public:
  enum Kind : unsigned char { Null, Constant, Equal, Atom };

  // Words first..first+2. null_ok: NULL leaves the component alone; atom_ok: atom-style variables allowed.
  void parse(const Args& a, std::size_t first, bool null_ok, bool atom_ok) {
    atom_ok_ = atom_ok;
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = first + k;
      const std::string& w = a.word(i, null_ok ? "a force component (number, v_name or NULL)"
                                               : "a force component (number or v_name)");
      at_[k] = i;
      if (w == "NULL") {
        if (!null_ok) a.fail(i, "a number or v_name (NULL is not allowed here, as in LAMMPS)");
        kind_[k] = Null;
      } else if (w.rfind("v_", 0) == 0 && w.size() > 2) {
        kind_[k] = Equal;  // or Atom: decided at init
        var_[k] = w.substr(2);
      } else {
        kind_[k] = Constant;
        value_[k] = a.num(i, null_ok ? "a force component (number, v_name or NULL)"
                                     : "a force component (number or v_name)");
      }
    }
  }

  // At init: each variable exists and has a style this fix accepts.
  void check(Simulation& sim, const Args& a) {
    for (int k = 0; k < 3; ++k) {
      if (kind_[k] != Equal && kind_[k] != Atom) continue;
      if (!sim.variables->exists(var_[k]))
        a.fail(at_[k], "a defined variable ('" + var_[k] + "' is not defined)");
      const bool atom = sim.variables->is_atom_style(var_[k]);
      if (atom && !atom_ok_) a.fail(at_[k], "an equal-style variable (v_" + var_[k] + " is atom-style)");
      kind_[k] = atom ? Atom : Equal;
    }
  }

  // Once a step, serially: the variables' values now.
  void evaluate(Simulation& sim, const Args& a) {
    for (int k = 0; k < 3; ++k) {
      if (kind_[k] == Equal && !sim.variables->numeric(var_[k], value_[k]))
        a.fail(at_[k], "a numeric variable (v_" + var_[k] + ")");
      if (kind_[k] == Atom) sim.variables->atom_values(var_[k], per_atom_[k]);
    }
  }

  bool active(int k) const { return kind_[k] != Null; }
  bool varying() const {
    for (int k = 0; k < 3; ++k)
      if (kind_[k] == Equal || kind_[k] == Atom) return true;
    return false;
  }
  bool constant(int k) const { return kind_[k] == Constant; }
  double value(int k) const { return value_[k]; }  // Constant or Equal (this step)
  double value(int k, std::size_t i) const { return kind_[k] == Atom ? per_atom_[k][i] : value_[k]; }
  // Never puts force out of the x-y plane: z left alone or set/added to zero.
  bool keeps_plane() const { return kind_[2] == Null || (kind_[2] == Constant && value_[2] == 0.0); }

 private:
  Kind kind_[3] = {Null, Null, Null};
  double value_[3] = {0, 0, 0};
  std::string var_[3];
  std::size_t at_[3] = {0, 0, 0};
  std::vector<double> per_atom_[3];
  bool atom_ok_ = true;
};

// `region ID` of the force fixes: the atom must also be inside it (LAMMPS).
// Looked up at definition and again at each init (the region may be redefined).
struct RegionOption {
  std::string name;
  std::size_t at = 0;
  const Region* region = nullptr;
  void parse(Simulation& sim, const Args& a, std::size_t i) {
    name = a.word(i, "a region ID");
    at = i;
    init(sim, a);
  }
  void init(Simulation& sim, const Args& a) {
    if (name.empty()) return;
    region = sim.find_region(name);
    if (!region) a.fail(at, "an existing region ID (define it with 'region' first)");
  }
  bool admits(const double* x) const { return !region || region->match(x); }
};

// The base of the three: fx fy fz at words 4..6, options from word 7, one
// post-force pass over the grains of the group (inside the region, if given).
class GroupForceFix : public Fix {
 public:
  void init() override {
    force_.check(sim, args);
    region_.init(sim, args);
  }

 protected:
  // null_ok, atom_ok: as ForceComponents::parse.
  GroupForceFix(Simulation& s, const Args& a, bool null_ok, bool atom_ok) : Fix(s, a) {
    hooks = atom_tasks = POST_FORCE;
    vector_size = 3;
    if (a.size() < 7)
      a.fail(a.size(), std::string("three force components fx fy fz ") + (null_ok ? "(number, v_name or NULL) " : "") +
                           "after '" + style + "'");
    force_.parse(a, 4, null_ok, atom_ok);
    traits.keeps_plane = force_.keeps_plane();
  }
  // setforce and aveforce take `region ID` and nothing else.
  void parse_region_only(const Args& a) {
    for (std::size_t i = 7; i < a.size(); i += 2) {
      if (a[i] != "region") a.fail(i, "region");
      region_.parse(sim, a, i + 1);
    }
  }
  bool member(std::size_t i) const {
    return (sim.atoms.mask[i] & groupbit) && region_.admits(&sim.atoms.x[3 * i]);
  }

  ForceComponents force_;
  RegionOption region_;
};

}  // namespace sable
