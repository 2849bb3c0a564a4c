#pragma once
// cohesion sjkr — LIGGGHTS 3.8's simplified JKR cohesion (gran_cohesion_sjkr.txt):
// while the surfaces overlap, a pull F = k A along the normal, k =
// cohesionEnergyDensity (J/m^3, peratomtypepair), A the contact area:
//   pair: A = pi a^2, a the radius of the circle where the spheres intersect
//         (mathworld Sphere-Sphere Intersection), r the centre distance:
//         A = pi/4 (ri+rj-r)(r+ri-rj)(r-ri+rj)(r+ri+rj) / r^2
//   wall: A = pi (ri^2 - r^2), r the centre-to-wall distance
// tangential_reduce off (default): the Coulomb cap and rolling friction see
// the normal force without the pull (LIGGGHTS adds it to the grains' force but
// to sidata.Fn only with tangential_reduce on).
// cohesion/sjkr2.h uses the same law with another area.
#include <numbers>

#include "contact_models/contact.h"
#include "contact_models/materials.h"

namespace sable {

// The pull k A of an area rule Area (static double area(const Contact&), kName).
template <class Area>
struct CohesionEnergyDensity : NoHistory {
  static constexpr const char* kName = Area::kName;
  static constexpr bool kActive = true;

  const double* k = nullptr;
  bool tangential_reduce = false;
  void settings(ModelSettings& s) { s.on_off("tangential_reduce", tangential_reduce); }
  void connect(PropertyRequest& p) { k = p.pair_table("cohesionEnergyDensity"); }
  bool reduces_tangential() const { return tangential_reduce; }
  double force(const Contact& c, const NormalForce&, double*, const StepContext&) const {
    return -k[c.tp] * Area::area(c);
  }
};

struct SjkrArea {
  static constexpr const char* kName = "sjkr";
  static double area(const Contact& c) {
    constexpr double pi = std::numbers::pi;
    const double r = c.r, ri = c.radi, rj = c.radj;
    const double pair = -pi / 4 * ((r - ri - rj) * (r + ri - rj) * (r - ri + rj) * (r + ri + rj)) / (r * r);
    const double wall = (ri * ri - r * r) * pi;
    return c.is_wall ? wall : pair;
  }
};
using CohesionSjkr = CohesionEnergyDensity<SjkrArea>;

}  // namespace sable

SABLE_COHESION_MODEL(sable::CohesionSjkr);
