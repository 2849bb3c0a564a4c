// fix ID group adapt N atom diameter v_name [scale no|yes] [reset no|yes]
// (LIGGGHTS/LAMMPS fix adapt, its atom diameter attribute): every N steps (N 0:
// once, at the start of each run), and at the start of each run, each grain of
// the group gets the diameter the variable gives (equal-style: all the same;
// atom-style: each its own), times its original diameter with `scale yes`. The
// mass follows at constant density (as LIGGGHTS does for granular atoms).
// `reset yes` restores the original diameters and masses after the run.
// Diameters change after the positions' update and before the rebuild check (the
// step's moment LIGGGHTS' pre_force has too: nothing in between reads sizes or
// masses), so the check counts the growth (Neighbor::radii_vary) before forces.
#include <cmath>

#include "core/engine/error.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/input/variable.h"

namespace sable {

class FixAdapt : public Fix {
 public:
  FixAdapt(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = POST_INTEGRATE;
    const long n = a.integer(4, "the period N (steps, 0: only at the start of each run)");
    if (n < 0) a.fail(4, "a period N >= 0");
    every_ = n;
    std::size_t i = 5;
    if (i >= a.size()) a.fail(i, "an attribute: 'atom diameter v_name' (sable supports the atom diameter attribute)");
    if (a[i] == "pair") a.fail(i, "'atom' (sable's fix adapt changes the atom diameter only; pair parameters are fixed)");
    if (a[i] != "atom") a.fail(i, "'atom'");
    if (a.word(i + 1, "'diameter'") != "diameter") a.fail(i + 1, "'diameter' (the only atom attribute sable adapts)");
    const std::string& v = a.word(i + 2, "v_name (an equal- or atom-style variable)");
    if (v.rfind("v_", 0) != 0 || v.size() < 3) a.fail(i + 2, "v_name (an equal- or atom-style variable)");
    var_ = v.substr(2);
    var_at_ = i + 2;
    for (i += 3; i < a.size(); i += 2) {
      if (a[i] == "scale") scale_ = a.yes_no(i + 1, "yes or no after 'scale'");
      else if (a[i] == "reset") reset_ = a.yes_no(i + 1, "yes or no after 'reset'");
      else a.fail(i, "'scale' or 'reset'");
    }
  }

  void init() override {
    if (!sim.variables->exists(var_)) args.fail(var_at_, "a defined variable ('" + var_ + "' is not defined)");
    atom_style_ = sim.variables->is_atom_style(var_);
    if (!atom_style_ && !sim.variables->is_equal_style(var_))
      args.fail(var_at_, "an equal- or atom-style variable (v_" + var_ + ")");
    sim.neighbor.radii_vary = true;
    if (scale_ || reset_) remember_originals();
    change();  // as LIGGGHTS: at the start of every run, whatever N
  }
  void post_integrate() override {
    if (every_ > 0 && sim.step % every_ == 0) change();
  }
  void post_run() override {
    if (!reset_) return;
    Atoms& at = sim.atoms;
    const auto& orig = at.column(orig_col_);
    for (std::size_t i = 0; i < at.n; ++i)
      if ((at.mask[i] & groupbit) && orig[i] > 0) at.set_radius_density(i, 0.5 * orig[i], at.density[i]);
    sim.neighbor.last_build_step = -1;
  }

 private:
  long every_ = 0;
  std::string var_;
  std::size_t var_at_ = 0;
  bool scale_ = false, reset_ = false, atom_style_ = false;
  int orig_col_ = -1;  // the diameters at the start of the run (0: not in the group then)
  std::vector<double> values_;

  void remember_originals() {
    Atoms& at = sim.atoms;
    orig_col_ = at.add_column("adapt:" + id, 1);
    auto& orig = at.column(orig_col_);
    for (std::size_t i = 0; i < at.n; ++i) orig[i] = (at.mask[i] & groupbit) ? 2.0 * at.radius[i] : 0.0;
  }

  void change() {
    Atoms& at = sim.atoms;
    double value = 0.0;
    if (atom_style_) sim.variables->atom_values(var_, values_);
    else if (!sim.variables->numeric(var_, value)) args.fail(var_at_, "a numeric variable (v_" + var_ + ")");
    const std::vector<double>* orig = scale_ ? &at.column(orig_col_) : nullptr;
    for (std::size_t i = 0; i < at.n; ++i) {
      if (!(at.mask[i] & groupbit)) continue;
      double d = atom_style_ ? values_[i] : value;
      if (orig) d *= (*orig)[i] > 0 ? (*orig)[i] : 2.0 * at.radius[i];  // grains inserted since: their own size
      if (!(d > 0) || !std::isfinite(d))
        fail("fix adapt " + id + ": v_" + var_ + " gives atom " + std::to_string(at.id[i]) + " the diameter " +
                  std::to_string(d) + " at step " + std::to_string(sim.step) + " (a diameter must be > 0)");
      at.set_radius_density(i, 0.5 * d, at.density[i]);
    }
  }
};

SABLE_FIX("adapt", FixAdapt);

}  // namespace sable
