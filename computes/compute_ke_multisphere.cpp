// compute ID group ke/multisphere: the translational kinetic energy 1/2 M vcm^2
// summed over the bodies of fix multisphere (LIGGGHTS 3.8: the group is ignored), a global scalar.
#include "computes/kinetic_energy.h"
#include "core/input/style_registry.h"

namespace sable {

SABLE_COMPUTE("ke/multisphere", BodyEnergyCompute<&FixMultisphere::kinetic_energy>);

}  // namespace sable
