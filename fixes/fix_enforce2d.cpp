// fix ID group enforce2d: zero v_z and f_z, and the x/y components of omega
// and torque, so grains stay in their plane (LIGGGHTS post_force). It must
// act after every other force: like LIGGGHTS, it runs in definition order, so
// it should be the last fix defined; a post-force fix defined after it is warned about.
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/engine/threads.h"

namespace sable {

class FixEnforce2d : public Fix {
 public:
  // --export-yade: the script locks z, X and Y of every grain in 2D (blockedDOFs).
  void export_yade(YadeScript&) const override {}
  FixEnforce2d(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = atom_tasks = POST_FORCE;
    traits.constraint = traits.keeps_plane = true;  // it only zeroes components
    if (a.size() > 4) a.fail(4, "nothing after 'enforce2d'");
    if (s.domain.dimension != 2) a.fail(3, "a 2D simulation for fix enforce2d ('dimension 2' before create_box)");
  }
  void init() override {
    for (const Fix* f : later_force_fixes())
      sim.warn("fix enforce2d " + id + ": fix " + f->style + " '" + f->id +
               "' is defined after it and may add out-of-plane force after enforce2d has run; "
               "define fix enforce2d last (as LIGGGHTS requires)");
  }
  void range(FixHook, const AtomRange& r) override {
    Atoms& at = sim.atoms;
    for (std::size_t i = r.lo; i < r.hi; ++i) {
      if (!(at.mask[i] & groupbit)) continue;
      at.v[3 * i + 2] = at.f[3 * i + 2] = 0;
      at.omega[3 * i] = at.omega[3 * i + 1] = 0;
      at.torque[3 * i] = at.torque[3 * i + 1] = 0;
    }
  }
};

SABLE_FIX("enforce2d", FixEnforce2d);

}  // namespace sable
