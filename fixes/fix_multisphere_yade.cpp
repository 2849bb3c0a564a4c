// fix multisphere in sable --export-yade (core/io/yade_script.h): each body one
// YADE clump of its member spheres with the body's own mass, inertia (from the
// template, about its principal axes) and state; every member carries the
// body's mass in contacts, as LIGGGHTS has it.
#include <algorithm>

#include <Eigen/Dense>

#include "core/engine/simulation.h"
#include "fixes/fix_multisphere.h"
#include "core/io/yade_script.h"

namespace sable {

void FixMultisphere::export_yade(YadeScript& s) const {
  const auto body = yade::members(sim, *this);
  std::vector<yade::Clump> out;
  for (std::size_t b = 0; b < bodies().size(); ++b) {
    const rigid::Body& r = this->body(static_cast<int>(b));
    yade::Clump c;
    for (std::size_t i : b < body.size() ? body[b] : std::vector<std::size_t>{}) c.ids.push_back(sim.atoms.id[i]);
    std::sort(c.ids.begin(), c.ids.end());
    c.mass = c.member_mass = r.mass;  // LIGGGHTS: every member carries the body's mass
    Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
    const rigid::V3* e[3] = {&r.ex, &r.ey, &r.ez};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a((*e[k])[0], (*e[k])[1], (*e[k])[2]);
      I += r.moments[k] * a * a.transpose();
    }
    const double v[6] = {I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)};
    std::copy(v, v + 6, c.inertia);
    for (int k = 0; k < 3; ++k) c.vcm[k] = r.vcm[k], c.omega[k] = r.omega[k];
    c.dofs = yade::dofs_of(r.fflag, r.tflag);
    out.push_back(c);
  }
  s.add_clumps(*this, out);
}

}  // namespace sable
