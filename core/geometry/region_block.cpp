// region ID block xlo xhi ylo yhi zlo zhi [side in|out] [units box|lattice]
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/geometry/region.h"
#include "core/input/style_registry.h"

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
  double area() const override { return (hi[0] - lo[0]) * (hi[1] - lo[1]); }
  double depth(const double* x, int dim) const override {
    double in = std::numeric_limits<double>::max(), out2 = 0;
    for (int k = 0; k < dim; ++k) {  // in 2D the z faces do not bound a disc at z = 0
      in = std::min({in, x[k] - lo[k], hi[k] - x[k]});
      const double e = std::max({lo[k] - x[k], x[k] - hi[k], 0.0});
      out2 += e * e;
    }
    return in >= 0 ? in : -std::sqrt(out2);
  }
};

SABLE_REGION("block", RegionBlock);

}  // namespace sable
