// compute ID group erotate/multisphere: the rotational kinetic energy 1/2 sum I_k w_k^2 (principal frame)
// summed over the bodies of fix multisphere (LIGGGHTS 3.8: the group is ignored), a global scalar.
#include "computes/kinetic_energy.h"
#include "core/input/style_registry.h"

namespace sable {

SABLE_COMPUTE("erotate/multisphere", BodyEnergyCompute<&FixMultisphere::rotational_energy>);

}  // namespace sable
