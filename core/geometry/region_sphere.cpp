// region ID sphere x y z radius [side in|out] [units box|lattice]
#include <cmath>
#include <numbers>

#include "core/geometry/region.h"
#include "core/input/style_registry.h"

namespace sable {

class RegionSphere : public Region {
 public:
  RegionSphere(Simulation& s, const Args& a) : Region(s, a) {
    a.need(7, "region ID sphere x y z radius");
    parse_options(a, 7);
    const double scale[3] = {xscale, yscale, zscale};
    for (int k = 0; k < 3; ++k) c_[k] = a.num(3 + k, "a centre coordinate") * scale[k];
    r_ = a.num(6, "the radius") * xscale;
    if (!(r_ > 0)) a.fail(6, "a radius > 0");
    for (int k = 0; k < 3; ++k) {
      lo[k] = c_[k] - r_;
      hi[k] = c_[k] + r_;
    }
  }
  bool inside(const double* x) const override {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += (x[k] - c_[k]) * (x[k] - c_[k]);
    return d2 <= r_ * r_;
  }
  double volume() const override { return 4.0 / 3.0 * std::numbers::pi * r_ * r_ * r_; }
  // (From the bounds, as fix insert has always computed it: the same bits.)
  double depth(const double* x, int) const override {
    double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += std::pow(x[k] - 0.5 * (lo[k] + hi[k]), 2);
    return 0.5 * (hi[0] - lo[0]) - std::sqrt(d2);
  }

 private:
  double c_[3] = {0, 0, 0}, r_ = 0;
};

SABLE_REGION("sphere", RegionSphere);

}  // namespace sable
