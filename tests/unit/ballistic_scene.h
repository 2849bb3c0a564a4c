#pragma once
// Shared by the ballistic_deposit tests (disks and clumps): the 2D box deck's
// prelude and the periodic contact gap.
#include <cmath>
#include <string>

namespace sable::test {

// A 2D box [0, W] x [0, H], periodic in x, fixed in y, one atom type.
inline std::string ballistic_box(double W, double H) {
  return "units si\natom_style granular\ndimension 2 grains disks\nboundary p f p\nregion box block 0 " +
         std::to_string(W) + " 0 " + std::to_string(H) + " -0.5 0.5 units box\ncreate_box 1 box\n";
}

// Centre distance of disks i and j over ri + rj, j's x image nearest i's (the
// box is wider than 4 radii, so no disk touches two images of another); jx
// gets that image's x.
template <class D>
double periodic_gap(const D& i, const D& j, double W, double* jx = nullptr) {
  const double x = j.x + W * std::round((i.x - j.x) / W);
  if (jx) *jx = x;
  return std::hypot(i.x - x, i.y - j.y) / (i.r + j.r);
}

}  // namespace sable::test
