#pragma once
// Rigid bodies of a deck as YADE clumps, for sable --export-yade
// (core/io/yade_script.h). Each body becomes one clump of its member spheres
// with sable's mass and inertia (YADE's own would come from the materials'
// density, ignoring the masses sable gave the grains), its centre-of-mass
// velocity and spin, and the degrees of freedom its force/torque flags lock.
// Fix rigid's bodies are made here, fix multisphere's next to it
// (fixes/fix_multisphere_yade.cpp) with the helpers below.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace sable {

class Simulation;
class Fix;

namespace yade {

struct Clump {
  std::vector<long> ids;   // member atom ids, ascending
  double mass = 0;
  double inertia[6] = {};  // about the centre of mass, world frame: xx yy zz xy xz yz
  double vcm[3] = {}, omega[3] = {};
  std::string dofs;        // YADE blockedDOFs: x/y/z for force flags off, X/Y/Z for torque flags off
  double member_mass = 0;  // the mass each member shows contacts (sable and LIGGGHTS: the body's)
};

// fix rigid / rigid/small: mass and inertia summed over the members (2/5 m r^2
// each plus the parallel-axis term; overlaps counted twice, as sable, LAMMPS and
// LIGGGHTS do), momentum from the members' velocities and spins, flags from the
// fix's `force` / `torque` keywords.
std::vector<Clump> rigid_clumps(const Simulation& sim, const Fix& fix);

// Members of each body of `fix` (its rigid_bodies()), by atom index, bodies in the fix's order.
std::vector<std::vector<std::size_t>> members(const Simulation& sim, const Fix& fix);
// blockedDOFs from flags: a force flag off keeps that velocity component, as YADE's blocked DOF does.
std::string dofs_of(const std::array<bool, 3>& force, const std::array<bool, 3>& torque);

}  // namespace yade
}  // namespace sable
