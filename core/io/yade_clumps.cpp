// Rigid bodies as YADE clumps (core/io/yade_clumps.h); fix multisphere's are
// made next to it (fixes/fix_multisphere_yade.cpp).
#include "core/io/yade_clumps.h"

#include <algorithm>
#include <array>

#include <Eigen/Dense>

#include "core/engine/rigid_bodies.h"
#include "core/engine/simulation.h"
#include "core/input/args.h"

namespace sable::yade {

std::vector<std::vector<std::size_t>> members(const Simulation& sim, const Fix& fix) {
  std::vector<std::vector<std::size_t>> m;
  const RigidBodies& rb = *fix.rigid_bodies();
  for (std::size_t i = 0; i < sim.atoms.n; ++i) {
    const int k = rb.body_of(i);
    if (k < 0) continue;
    if (static_cast<std::size_t>(k) >= m.size()) m.resize(k + 1);
    m[k].push_back(i);
  }
  return m;
}

std::string dofs_of(const std::array<bool, 3>& f, const std::array<bool, 3>& t) {
  std::string d;
  for (int k = 0; k < 3; ++k)
    if (!f[k]) d += "xyz"[k];
  for (int k = 0; k < 3; ++k)
    if (!t[k]) d += "XYZ"[k];
  return d;
}

namespace {

void store_inertia(const Eigen::Matrix3d& I, Clump& c) {
  const double v[6] = {I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)};
  std::copy(v, v + 6, c.inertia);
}

// Bodies lo..hi (1-based) named by a LAMMPS range: M, *, *n, n*, m*n.
void body_range(const Args& a, std::size_t at, long nb, long& lo, long& hi) {
  const std::string& r = a[at];
  const auto star = r.find('*');
  auto number = [&](const std::string& s) {
    long v;
    if (!parse_long(s, v)) a.fail(at, "a body number M, or a range *, *n, n*, m*n");
    return v;
  };
  lo = 1, hi = nb;
  if (star == std::string::npos) lo = hi = number(r);
  else {
    if (star > 0) lo = number(r.substr(0, star));
    if (star + 1 < r.size()) hi = number(r.substr(star + 1));
  }
}

// The `force M x y z` / `torque M x y z` keywords of fix rigid, as fixes/fix_rigid.cpp reads them.
void rigid_flags(const Fix& fix, std::vector<std::array<bool, 3>>& ff, std::vector<std::array<bool, 3>>& tf) {
  const Args& a = fix.args;  // fix ID group rigid bodystyle ...
  std::size_t i = 5;
  if (a.word(4, "a body style") == "group") i = 6 + a.integer(5, "the number of groups");
  else if (a[4] == "custom") i = 6;
  for (; i + 4 < a.size(); i += 5) {
    long lo, hi;
    body_range(a, i + 1, static_cast<long>(ff.size()), lo, hi);
    for (long b = lo; b <= hi && b <= static_cast<long>(ff.size()); ++b)
      for (int k = 0; k < 3; ++k) (a[i] == "torque" ? tf : ff)[b - 1][k] = a.yes_no(i + 2 + k, "on or off");
  }
}

// Angular velocity from angular momentum, zero about an axis whose moment is
// under 1e-7 of the largest (fixes/rigid_body_set.cpp: no spin about it).
Eigen::Vector3d spin(const Eigen::Matrix3d& I, const Eigen::Vector3d& L) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I);
  const Eigen::Vector3d m = eig.eigenvalues();
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d e = eig.eigenvectors().col(k);
    if (m(k) > 1e-7 * m.maxCoeff()) w += e * (e.dot(L) / m(k));
  }
  return w;
}

}  // namespace

std::vector<Clump> rigid_clumps(const Simulation& sim, const Fix& fix) {
  const Atoms& at = sim.atoms;
  const auto body = members(sim, fix);
  std::vector<std::array<bool, 3>> ff(body.size(), {true, true, true}), tf = ff;
  rigid_flags(fix, ff, tf);
  std::vector<Clump> out;
  for (std::size_t b = 0; b < body.size(); ++b) {
    Clump c;
    Eigen::Vector3d xm = Eigen::Vector3d::Zero(), p = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3d> x;
    for (std::size_t i : body[b]) {
      double u[3];
      sim.domain.unmap(&at.x[3 * i], &at.image[3 * i], u);
      x.emplace_back(u[0], u[1], u[2]);
      c.mass += at.rmass[i];
      xm += at.rmass[i] * x.back();
      p += at.rmass[i] * Eigen::Vector3d(at.v[3 * i], at.v[3 * i + 1], at.v[3 * i + 2]);
      c.ids.push_back(at.id[i]);
    }
    xm /= c.mass;
    Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
    Eigen::Vector3d L = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < body[b].size(); ++k) {
      const std::size_t i = body[b][k];
      const double m = at.rmass[i];
      const Eigen::Vector3d d = x[k] - xm, v(at.v[3 * i], at.v[3 * i + 1], at.v[3 * i + 2]);
      I += (at.inertia(i) + m * d.squaredNorm()) * Eigen::Matrix3d::Identity() - m * d * d.transpose();
      L += m * d.cross(v) + at.inertia(i) * Eigen::Vector3d(at.omega[3 * i], at.omega[3 * i + 1], at.omega[3 * i + 2]);
    }
    store_inertia(I, c);
    const Eigen::Vector3d w = spin(I, L);
    for (int k = 0; k < 3; ++k) c.vcm[k] = p(k) / c.mass, c.omega[k] = w(k);
    c.dofs = dofs_of(ff[b], tf[b]);
    c.member_mass = c.mass;
    std::sort(c.ids.begin(), c.ids.end());
    out.push_back(c);
  }
  return out;
}

}  // namespace sable::yade
