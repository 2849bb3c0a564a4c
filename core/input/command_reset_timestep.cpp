// reset_timestep N (LAMMPS/LIGGGHTS): the step counter jumps to N between
// runs. As LIGGGHTS 3.8 does, the simulated time moves by (N - step) dt (not
// below 0) and what waits for a step moves with the counter: mesh poses here;
// insertion fixes see the jump at their next init (fixes/fix_insert.cpp).
// Dumps and thermo go on writing at multiples of their periods (step % every).
#include <algorithm>

#include "core/geometry/mesh.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {
namespace {

void cmd_reset_timestep(Simulation& sim, const Args& a) {
  const long n = a.integer(1, "the new step number");
  if (n < 0) a.fail(1, "a step number >= 0");
  if (a.size() > 2) a.fail(2, "nothing more (reset_timestep N)");
  const long delta = n - sim.step;
  sim.time = std::max(0.0, sim.time + static_cast<double>(delta) * sim.dt);
  for (auto& f : sim.fixes)
    if (auto* m = dynamic_cast<MeshHolder*>(f.get()); m && m->mesh().pose_step >= 0) m->mesh().pose_step += delta;
  sim.step = n;
}

}  // namespace

SABLE_COMMAND("reset_timestep", cmd_reset_timestep);

}  // namespace sable
