// displace_atoms GROUP move dx dy dz | ramp D dlo dhi C clo chi | rotate Px Py Pz Rx Ry Rz theta  [units box]
// LAMMPS / LIGGGHTS 3.8 semantics, between runs: positions change, velocities
// do not. ramp: each grain moves along D by dlo + f (dhi - dlo), f its place
// between clo and chi along C clamped to [0, 1]; rotate: theta degrees about
// the axis R through P (right hand; z left alone in 2D). Afterwards grains are
// wrapped into periodic boxes (image counters follow); the next run rebuilds
// the neighbour list in its setup. Units: box only (LIGGGHTS' default; LAMMPS'
// is lattice), `units lattice` is refused. `random` is not supported.
#include <cmath>
#include <numbers>

#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {
namespace {

int axis_word(const Args& a, std::size_t i) { return a.choice(i, {"x", "y", "z"}); }

// The units keyword after the style's arguments: box only.
void parse_units(const Args& a, std::size_t from) {
  a.box_units_only(from, "units (or nothing) after the displacement",
                   "box (sable's displace_atoms takes box units only; give distances in box units)");
}

template <class Move>
void each_member(Simulation& sim, std::uint32_t bit, Move&& move) {
  Atoms& at = sim.atoms;
  for (std::size_t i = 0; i < at.n; ++i)
    if (at.mask[i] & bit) move(&at.x[3 * i]);
}

void cmd_displace_atoms(Simulation& sim, const Args& a) {
  if (!sim.domain.box_exists) a.fail(0, "a box first (create_box before displace_atoms)");
  const std::uint32_t bit = sim.groups.bit(sim.groups.existing(a, 1));
  const std::string& style = a.word(2, "move, ramp or rotate");
  if (style == "move") {
    double d[3];
    for (int k = 0; k < 3; ++k) d[k] = a.num(3 + k, "a displacement dx dy dz");
    parse_units(a, 6);
    each_member(sim, bit, [&](double* x) {
      for (int k = 0; k < 3; ++k) x[k] += d[k];
    });
  } else if (style == "ramp") {
    const int dd = axis_word(a, 3);
    const double dlo = a.num(4, "the displacement at the low end"), dhi = a.num(5, "the displacement at the high end");
    const int cd = axis_word(a, 6);
    const double clo = a.num(7, "the low coordinate"), chi = a.num(8, "the high coordinate");
    if (chi == clo) a.fail(8, "a high coordinate different from the low one");
    parse_units(a, 9);
    each_member(sim, bit, [&](double* x) {
      const double f = std::min(std::max((x[cd] - clo) / (chi - clo), 0.0), 1.0);
      x[dd] += dlo + f * (dhi - dlo);
    });
  } else if (style == "rotate") {
    double p[3], r[3], len = 0;
    for (int k = 0; k < 3; ++k) p[k] = a.num(3 + k, "a point on the rotation axis (Px Py Pz)");
    for (int k = 0; k < 3; ++k) {
      r[k] = a.num(6 + k, "the rotation axis vector (Rx Ry Rz)");
      len += r[k] * r[k];
    }
    if (len == 0) a.fail(6, "a non-zero rotation axis vector");
    const bool flat = sim.domain.dimension == 2;
    if (flat && (r[0] != 0 || r[1] != 0)) a.fail(6, "an axis along z (2D rotates about z only)");
    for (double& c : r) c /= std::sqrt(len);
    const double theta = a.num(9, "the rotation angle (degrees)") * std::numbers::pi / 180.0;
    parse_units(a, 10);
    const double c = std::cos(theta), s = std::sin(theta);
    each_member(sim, bit, [&](double* x) {
      double d[3], along[3], q[3];
      for (int k = 0; k < 3; ++k) d[k] = x[k] - p[k];
      const double dr = d[0] * r[0] + d[1] * r[1] + d[2] * r[2];
      for (int k = 0; k < 3; ++k) along[k] = dr * r[k], q[k] = d[k] - along[k];
      const double b[3] = {r[1] * q[2] - r[2] * q[1], r[2] * q[0] - r[0] * q[2], r[0] * q[1] - r[1] * q[0]};
      for (int k = 0; k < (flat ? 2 : 3); ++k) x[k] = p[k] + along[k] + (q[k] * c + b[k] * s);
    });
  } else if (style == "random") {
    a.fail(2, "move, ramp or rotate ('random' is not supported)");
  } else {
    a.fail(2, "move, ramp or rotate");
  }
  Atoms& at = sim.atoms;
  for (std::size_t i = 0; i < at.n; ++i)
    if (std::isfinite(at.x[3 * i]) && std::isfinite(at.x[3 * i + 1]) && std::isfinite(at.x[3 * i + 2]))
      sim.domain.remap(&at.x[3 * i], &at.image[3 * i]);
  for (auto& c : sim.computes) c->reset_cache();  // values cached at this step saw the old positions
  sim.print("Displacing atoms ...");
}

}  // namespace

SABLE_COMMAND("displace_atoms", cmd_displace_atoms);

}  // namespace sable
