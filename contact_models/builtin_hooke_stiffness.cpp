// Pre-instantiates model hooke/stiffness with every built-in tangential and rolling model
// (one file per normal model so the 36 kernels compile in parallel).
#include "contact_models/registry.h"

namespace sable {
SABLE_GRAN_NORMAL(NormalHookeStiffness);
}
