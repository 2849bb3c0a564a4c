// region ID block xlo xhi ylo yhi zlo zhi [side in|out] [units box|lattice]
#include "core/region.h"
#include "core/style_registry.h"

namespace sable {

class RegionBlock : public Region {
 public:
  RegionBlock(Simulation& s, const Args& a) : Region(s, a) {
    a.need(9, "region ID block xlo xhi ylo yhi zlo zhi");
    parse_options(a, 9);
    const double scale[3] = {xscale, yscale, zscale};
    for (int k = 0; k < 3; ++k) {
      lo[k] = coord(a, 3 + 2 * k, k, false) * scale[k];
      hi[k] = coord(a, 4 + 2 * k, k, true) * scale[k];
      if (!(hi[k] > lo[k])) a.fail(4 + 2 * k, "an upper bound greater than the lower bound");
    }
  }
  bool inside(const double* x) const override {
    for (int k = 0; k < 3; ++k)
      if (x[k] < lo[k] || x[k] > hi[k]) return false;
    return true;
  }
  double volume() const override { return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]); }
};

SABLE_REGION("block", RegionBlock);

}  // namespace sable
