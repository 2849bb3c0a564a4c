#pragma once
// Base of regions (LIGGGHTS `region ID style args [side in|out] [units box]`).
#include <string>

#include "core/input/args.h"

namespace sable {

class Simulation;

class Region {
 public:
  Region(Simulation& sim, const Args& args);
  virtual ~Region() = default;
  std::string id, style;
  bool interior = true;  // side in
  bool match(const double* x) const { return inside(x) == interior; }
  virtual bool inside(const double* x) const = 0;
  // Axis-aligned bounds of the inside (for insertion and lattices).
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  // Volume of the inside, for packing fractions (0 when unknown); area(): of its
  // section by the plane z = 0, for 2D decks (0 when unknown).
  virtual double volume() const { return 0.0; }
  virtual double area() const { return 0.0; }
  // Signed distance from x to the surface of the inside (> 0 inside) in `dim`
  // dimensions (2D: what bounds a disc at z = 0); NaN when the style has none.
  virtual double depth(const double* x, int dim) const;

 protected:
  Simulation& sim;
  // Parse trailing `side in|out` and `units box|lattice`; returns first index not consumed.
  void parse_options(const Args& args, std::size_t from);
  double xscale = 1.0, yscale = 1.0, zscale = 1.0;  // lattice units
  // Number, or INF/-INF/EDGE words meaning the box bound on this axis.
  double coord(const Args& args, std::size_t i, int axis, bool upper) const;
};

}  // namespace sable
