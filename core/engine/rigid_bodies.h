#pragma once
// The rigid-body role (fix rigid, rigid/small, multisphere): what core,
// computes, dumps and tools ask of a fix that moves grains as members of
// bodies, reached through Fix::rigid_bodies(). Bodies go by the deck's
// numbers (from 0; f_ID row - 1), stable over the run. Such a fix is the
// integrator of its bodies' grains: no other fix may integrate them.
#include <cstddef>

namespace sable {

class RigidBodies {
 public:
  // The body of atom i (-1: in none of these bodies).
  virtual int body_of(std::size_t i) const = 0;
  // A body's summed force as the last step applied it (per-body statistics).
  virtual const double* body_force(int body) const = 0;
  // Bodies whose member grains carry the body's mass (fix multisphere): true and
  // their 1/2 M vcm^2, which thermo ke counts once per body in place of the members'.
  virtual bool body_kinetic_energy(double& /*ke*/) const { return false; }

 protected:
  ~RigidBodies() = default;
};

}  // namespace sable
