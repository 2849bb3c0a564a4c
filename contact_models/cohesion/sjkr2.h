#pragma once
// cohesion sjkr2 — LIGGGHTS 3.8's modified simplified JKR cohesion
// (gran_cohesion_sjkr2.txt): the pull k A of cohesion sjkr (cohesion/sjkr.h:
// cohesionEnergyDensity, tangential_reduce) with the area of a cap of the
// contact sphere instead of the intersection circle:
//   pair: A = 2 pi (2 R*) dn     wall: A = 2 pi ri dn
// (the wall's R* is ri, so both are 2 pi dn times the harmonic-mean radius).
#include <numbers>

#include "contact_models/cohesion/sjkr.h"

namespace sable {

struct Sjkr2Area {
  static constexpr const char* kName = "sjkr2";
  static double area(const Contact& c) {
    constexpr double pi = std::numbers::pi;
    const double r = c.r, ri = c.radi, rj = c.radj;
    const double pair = pi * 2. * (2. * ri * rj / (ri + rj)) * (ri + rj - r);
    const double wall = pi * 2. * ri * (ri - r);
    return c.is_wall ? wall : pair;
  }
};
using CohesionSjkr2 = CohesionEnergyDensity<Sjkr2Area>;

}  // namespace sable

SABLE_COHESION_MODEL(sable::CohesionSjkr2);
