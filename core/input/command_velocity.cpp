// velocity GROUP set vx vy vz | ramp vdim vlo vhi dim clo chi | zero linear|angular
//          [sum yes|no] [units box|lattice] [dist ...] [mom ...] [rot ...] [loop ...]
// LIGGGHTS 3.8 `velocity` for granular decks (units default to box, unlike LAMMPS).
// set: NULL keeps a component; a value may be v_name (equal- or atom-style).
// zero: removes the group's mass-weighted linear momentum, or its angular
// momentum about the centre of mass (grain spins are not touched).
// `create` (thermal velocities) is not supported: granular decks do not use it.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/engine/error.h"
#include "core/input/expression.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/input/variable.h"

namespace sable {
namespace {

void zero_linear(Atoms& at, std::uint32_t bit) {
  double p[3] = {0, 0, 0}, m = 0;
  for (std::size_t i = 0; i < at.n; ++i)
    if (at.mask[i] & bit) {
      m += at.rmass[i];
      for (int k = 0; k < 3; ++k) p[k] += at.rmass[i] * at.v[3 * i + k];
    }
  if (m <= 0) return;
  for (std::size_t i = 0; i < at.n; ++i)
    if (at.mask[i] & bit)
      for (int k = 0; k < 3; ++k) at.v[3 * i + k] -= p[k] / m;
}

void zero_angular(Atoms& at, const Domain& d, std::uint32_t bit) {
  using Eigen::Vector3d;
  std::vector<Vector3d> x(at.n);
  Vector3d xcm = Vector3d::Zero();
  double m = 0;
  for (std::size_t i = 0; i < at.n; ++i)
    if (at.mask[i] & bit) {
      d.unmap(&at.x[3 * i], &at.image[3 * i], x[i].data());  // unwrapped: a group across a periodic face stays whole
      xcm += at.rmass[i] * x[i];
      m += at.rmass[i];
    }
  if (m <= 0) return;
  xcm /= m;
  Vector3d L = Vector3d::Zero();
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < at.n; ++i)
    if (at.mask[i] & bit) {
      const Vector3d r = x[i] - xcm, v(at.v[3 * i], at.v[3 * i + 1], at.v[3 * i + 2]);
      L += at.rmass[i] * r.cross(v);
      I += at.rmass[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    }
  // Pseudo-inverse: a line of grains (or one grain) has a singular inertia tensor.
  const Vector3d w = I.completeOrthogonalDecomposition().solve(L);
  for (std::size_t i = 0; i < at.n; ++i)
    if (at.mask[i] & bit) {
      const Vector3d dv = w.cross(x[i] - xcm);
      for (int k = 0; k < 3; ++k) at.v[3 * i + k] -= dv[k];
    }
}

void cmd_velocity(Simulation& sim, const Args& a) {
  if (!sim.domain.box_exists) a.fail(0, "a box first (create_box before velocity)");
  const std::uint32_t bit = sim.groups.bit(sim.groups.existing(a, 1));
  const std::string& style = a.word(2, "set, ramp or zero");
  std::size_t opt = 0;
  if (style == "set")
    opt = 6;
  else if (style == "ramp")
    opt = 9;
  else if (style == "zero")
    opt = 4;
  else if (style == "create" || style == "scale" || style == "setAngular")
    a.fail(2, "set, ramp or zero ('" + style + "' is not supported by sable; granular decks set velocities)");
  else
    a.fail(2, "set, ramp or zero");

  bool sum = false, lattice = false;
  for (std::size_t i = opt; i < a.size(); i += 2) {
    const std::string& k = a[i];
    if (k == "sum")
      sum = a.yes_no(i + 1, "yes or no");
    else if (k == "units") {
      lattice = a.choice(i + 1, {"box", "lattice"}) == 1;
    } else if (k == "mom" || k == "rot")
      a.yes_no(i + 1, "yes or no");
    else if (k == "dist") {
      a.choice(i + 1, {"uniform", "gaussian"});
    } else if (k == "loop") {
      a.choice(i + 1, {"all", "local", "geom"});
    } else
      a.fail(i, "a velocity keyword: sum, units, mom, rot, dist, loop");
  }
  if (lattice && sim.lattice.style == "none") a.fail_line("units lattice needs a lattice (use the lattice command)");
  const double* scale = lattice ? sim.lattice.a : nullptr;
  Atoms& at = sim.atoms;

  if (style == "zero") {
    const std::string& what = a.word(3, "linear or angular");
    if (what == "linear")
      zero_linear(at, bit);
    else if (what == "angular")
      zero_angular(at, sim.domain, bit);
    else
      a.fail(3, "linear or angular");
    return;
  }
  if (style == "set") {
    for (int k = 0; k < 3; ++k) {
      const std::size_t w = 3 + k;
      const std::string& s = a.word(w, "a velocity component, NULL or v_name");
      if (s == "NULL") continue;
      std::vector<double> per;
      double val = 0;
      if (s.rfind("v_", 0) == 0) {
        const std::string name = s.substr(2);
        if (!sim.variables->exists(name)) a.fail(w, "an existing variable after v_ (no variable '" + name + "')");
        try {
          sim.variables->atom_values(name, per);
        } catch (const ExpressionError& e) {
          a.fail(w, std::string("a variable that evaluates (") + e.what() + ")");
        }
      } else {
        val = a.num(w, "a velocity component, NULL or v_name");
        if (k == 2 && sim.domain.dimension == 2 && val != 0) a.fail(w, "0 or NULL (vz in a 2D simulation)");
      }
      for (std::size_t i = 0; i < at.n; ++i) {
        if (!(at.mask[i] & bit)) continue;
        const double v = (per.empty() ? val : per[i]) * (scale ? scale[k] : 1.0);
        at.v[3 * i + k] = sum ? at.v[3 * i + k] + v : v;
      }
    }
    return;
  }
  // ramp vdim vlo vhi dim clo chi: v grows linearly with the coordinate, clamped outside [clo, chi].
  auto axis = [&](std::size_t w, const std::string& prefix) {
    const std::string& s = a.word(w, prefix + "x, " + prefix + "y or " + prefix + "z");
    if (s.size() != prefix.size() + 1 || s.compare(0, prefix.size(), prefix) != 0 || s.back() < 'x' || s.back() > 'z')
      a.fail(w, prefix + "x, " + prefix + "y or " + prefix + "z");
    return s.back() - 'x';
  };
  const int vd = axis(3, "v"), cd = axis(6, "");
  const double vs = scale ? scale[vd] : 1.0, cs = scale ? scale[cd] : 1.0;
  const double vlo = a.num(4, "the low velocity") * vs, vhi = a.num(5, "the high velocity") * vs;
  const double clo = a.num(7, "the low coordinate") * cs, chi = a.num(8, "the high coordinate") * cs;
  if (!(chi > clo)) a.fail(8, "a high coordinate above the low one");
  if (vd == 2 && sim.domain.dimension == 2 && (vlo != 0 || vhi != 0)) a.fail(3, "vx or vy (no vz in 2D)");
  for (std::size_t i = 0; i < at.n; ++i) {
    if (!(at.mask[i] & bit)) continue;
    const double f = std::clamp((at.x[3 * i + cd] - clo) / (chi - clo), 0.0, 1.0);
    const double v = vlo + f * (vhi - vlo);
    at.v[3 * i + vd] = sum ? at.v[3 * i + vd] + v : v;
  }
}

}  // namespace

SABLE_COMMAND("velocity", cmd_velocity);

}  // namespace sable
