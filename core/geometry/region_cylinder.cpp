// region ID cylinder dim c1 c2 radius lo hi [side in|out] [units box|lattice]
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/geometry/region.h"
#include "core/input/style_registry.h"

namespace sable {

class RegionCylinder : public Region {
 public:
  RegionCylinder(Simulation& s, const Args& a) : Region(s, a) {
    a.need(9, "region ID cylinder dim c1 c2 radius lo hi");
    const std::string& d = a[3];
    if (d != "x" && d != "y" && d != "z") a.fail(3, "the cylinder axis x, y or z");
    axis_ = d[0] - 'x';
    parse_options(a, 9);
    const double scale[3] = {xscale, yscale, zscale};
    const int p = (axis_ + 1) % 3, q = (axis_ + 2) % 3;
    // c1, c2 are the two other coordinates in x, y, z order
    const int c1 = std::min(p, q), c2 = std::max(p, q);
    c_[0] = a.num(4, "the first centre coordinate") * scale[c1];
    c_[1] = a.num(5, "the second centre coordinate") * scale[c2];
    r_ = a.num(6, "the radius") * scale[c1];
    if (!(r_ > 0)) a.fail(6, "a radius > 0");
    a_lo_ = coord(a, 7, axis_, false) * scale[axis_];
    a_hi_ = coord(a, 8, axis_, true) * scale[axis_];
    ax1_ = c1;
    ax2_ = c2;
    lo[c1] = c_[0] - r_;
    hi[c1] = c_[0] + r_;
    lo[c2] = c_[1] - r_;
    hi[c2] = c_[1] + r_;
    lo[axis_] = a_lo_;
    hi[axis_] = a_hi_;
  }
  bool inside(const double* x) const override {
    if (x[axis_] < a_lo_ || x[axis_] > a_hi_) return false;
    const double d1 = x[ax1_] - c_[0], d2 = x[ax2_] - c_[1];
    return d1 * d1 + d2 * d2 <= r_ * r_;
  }
  double volume() const override { return std::numbers::pi * r_ * r_ * (a_hi_ - a_lo_); }
  // (From the bounds, as fix insert has always computed it: the same bits.)
  double depth(const double* x, int dim) const override {
    double rho2 = 0;
    for (int k = 0; k < 3; ++k)
      if (k != axis_) rho2 += std::pow(x[k] - 0.5 * (lo[k] + hi[k]), 2);
    const int p = (axis_ + 1) % 3;
    const double dr = 0.5 * (hi[p] - lo[p]) - std::sqrt(rho2);
    const bool axial = !(dim == 2 && axis_ == 2);  // a z cylinder in 2D is a disc
    const double da = axial ? std::min(x[axis_] - lo[axis_], hi[axis_] - x[axis_]) : dr;
    if (dr >= 0 && da >= 0) return std::min(dr, da);
    return -std::hypot(std::max(-dr, 0.0), std::max(-da, 0.0));
  }

 private:
  int axis_ = 2, ax1_ = 0, ax2_ = 1;
  double c_[2] = {0, 0}, r_ = 0, a_lo_ = 0, a_hi_ = 0;
};

SABLE_REGION("cylinder", RegionCylinder);

}  // namespace sable
