// fix ID group viscous gamma [scale type ratio ...]: F = -gamma_type v
// (LIGGGHTS/LAMMPS; gamma in force/velocity units, scaled per atom type).
#include <vector>

#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

class FixViscous : public Fix {
 public:
  FixViscous(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = atom_tasks = POST_FORCE;
    traits.keeps_plane = true;  // -gamma v: v_z is already 0
    const double g = a.num(4, "the damping coefficient gamma (N s/m)");
    if (g < 0) a.fail(4, "gamma >= 0");
    gamma_.assign(s.atoms.ntypes + 1, g);
    for (std::size_t i = 5; i < a.size(); i += 3) {
      if (a[i] != "scale") a.fail(i, "'scale type ratio' (the only fix viscous keyword)");
      const long t = a.integer(i + 1, "an atom type");
      if (t < 1 || t > s.atoms.ntypes) a.fail(i + 1, "an atom type between 1 and " + std::to_string(s.atoms.ntypes));
      gamma_[t] = g * a.num(i + 2, "the scale factor for this type");
    }
  }
  void range(FixHook, const AtomRange& r) override {
    Atoms& at = sim.atoms;
    for (std::size_t i = r.lo; i < r.hi; ++i) {
      if (!(at.mask[i] & groupbit)) continue;
      const double g = gamma_[at.type[i]];
      for (int k = 0; k < 3; ++k) at.f[3 * i + k] -= g * at.v[3 * i + k];
    }
  }

 private:
  std::vector<double> gamma_;  // per type, index 1..ntypes
};

SABLE_FIX("viscous", FixViscous);

}  // namespace sable
