// compute_modify ID keyword value ... (LAMMPS/LIGGGHTS). The keywords concern
// temperature computes: `dynamic yes|no` (or `dynamic/dof`: recount the atoms at
// each evaluation) and `extra N` (or `extra/dof`: degrees of freedom to subtract).
// sable has no temperature compute and no thermo `temp` (granular decks read `ke`),
// and its computes count the atoms of each evaluation anyway, so the keywords are
// checked and change nothing. ID is an existing compute or LIGGGHTS' default
// `thermo_temp`.
#include <cmath>

#include "core/engine/compute.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {
namespace {

void cmd_compute_modify(Simulation& sim, const Args& a) {
  const std::string& id = a.word(1, "a compute ID");
  if (id != "thermo_temp" && !sim.find_compute(id)) a.fail(1, "an existing compute ID (or thermo_temp)");
  if (a.size() < 4) a.fail(a.size(), "keyword value pairs: dynamic yes|no, extra N");
  for (std::size_t i = 2; i < a.size(); i += 2) {
    const std::string& k = a[i];
    if (k == "dynamic" || k == "dynamic/dof") {
      a.yes_no(i + 1, "yes or no after '" + k + "'");
    } else if (k == "extra" || k == "extra/dof") {
      const double n = a.num(i + 1, "a number of degrees of freedom after '" + k + "'");
      if (!std::isfinite(n)) a.fail(i + 1, "a finite number");
    } else {
      a.fail(i, "dynamic, dynamic/dof, extra or extra/dof (the keywords sable accepts)");
    }
  }
}

}  // namespace

SABLE_COMMAND("compute_modify", cmd_compute_modify);

}  // namespace sable
