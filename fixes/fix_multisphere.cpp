// fix multisphere; see fixes/fix_multisphere.h.
#include "fixes/fix_multisphere.h"

#include <cmath>

#include "core/io/restart.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {

// declarations, not `using namespace rigid`: in a unity batch a directive would reach the next files
using rigid::Body;
using rigid::BodySet;
using rigid::Q4;
using rigid::V3;

namespace {

Q4 product(const Q4& a, const Q4& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

// Pair-exclusion keys of multisphere bodies: above those of fix rigid (ordinal * 2^32 + body).
constexpr double kExclusionBase = 0x1.0p44;

}  // namespace

std::vector<V3> clump_offsets(const ClumpShape& shape, const Q4& q_ins, Q4& q_body) {
  q_body = product(q_ins, shape.q);
  rigid::normalize(q_body);
  V3 ex, ey, ez;
  rigid::axes(q_body, ex, ey, ez);
  std::vector<V3> d;
  for (const auto& o : shape.displace)
    d.push_back({o[0] * ex[0] + o[1] * ey[0] + o[2] * ez[0], o[0] * ex[1] + o[1] * ey[1] + o[2] * ez[1],
                 o[0] * ex[2] + o[1] * ey[2] + o[2] * ez[2]});
  return d;
}

FixMultisphere::FixMultisphere(Simulation& s, const Args& a) : Fix(s, a), set_(s) {
  hooks = INITIAL_INTEGRATE | FINAL_INTEGRATE;
  traits.turns_grains = true;     // bodies inserted later may turn
  set_.members_carry_mass = true;  // LIGGGHTS' convention (fixes/fix_multisphere.h)
  for (std::size_t i = 4; i < a.size(); i += 2) {
    if (a[i] == "allow_group_and_set" || a[i] == "allow_heatsource") {
      a.yes_no(i + 1, "yes or no");  // sable has neither restriction nor heat transfer
    } else {
      a.fail(i, "a fix multisphere keyword: allow_group_and_set or allow_heatsource (CAddRhoFluid is not supported)");
    }
  }
  for (auto& f : s.fixes)
    if (dynamic_cast<const FixMultisphere*>(f.get()) && f->id != id) a.fail(3, "one fix multisphere only (LIGGGHTS: exactly one; '" + f->id + "' exists)");
  if (s.domain.dimension != 3) a.fail(3, "dimension 3 (LIGGGHTS: fix multisphere works with 3D simulations only)");
  set_.col = s.atoms.add_column("multisphere:" + id, BodySet::kStride);
}

void FixMultisphere::init() {
  set_.find_damping();
  pair_col_ = sim.atoms.add_column("rigid:pair_exclusion", 1);
  sim.atoms.pair_exclusion = pair_col_;
  std::vector<int> count(set_.bodies.size(), 0);
  for (std::size_t i = 0; i < sim.atoms.n; ++i)
    if (const int k = set_.body_of_atom(i); k >= 0) ++count[k];
  for (std::size_t b = 0; b < count.size(); ++b)
    if (count[b] != set_.bodies[b].members)
      args.fail_line("multisphere body " + std::to_string(set_.number_of(static_cast<int>(b)) + 1) + " had " +
                     std::to_string(set_.bodies[b].members) + " spheres and has " + std::to_string(count[b]) + " now (spheres of a clump were deleted)");
  set_.place_members(false);
}

void FixMultisphere::setup() { sum_forces(); }

void FixMultisphere::initial_integrate() { set_.initial_integrate(sim.dt); }

void FixMultisphere::final_integrate() {
  sum_forces();
  set_.final_integrate(sim.dt);
}

// Member forces summed, then gravity as LIGGGHTS applies it: M g on each body
// at its centre of mass, none on the members (sable's fix gravity gave each
// member its rmass g, which is taken back out here).
void FixMultisphere::sum_forces() {
  set_.sum_forces();
  const Atoms& at = sim.atoms;
  const auto& c = at.column(set_.col);
  for (auto& f : sim.fixes) {
    if (f->traits.acceleration_norm() == 0) continue;
    const double* g = f->traits.acceleration;
    for (std::size_t i = 0; i < at.n; ++i) {
      const int k = set_.body_of_atom(i);
      if (k < 0 || !(at.mask[i] & f->groupbit)) continue;
      Body& b = set_.bodies[k];
      const V3 mg{at.rmass[i] * g[0], at.rmass[i] * g[1], at.rmass[i] * g[2]};
      const V3 t = rigid::cross(V3{c[BodySet::kStride * i + 4], c[BodySet::kStride * i + 5], c[BodySet::kStride * i + 6]}, mg);
      for (int e = 0; e < 3; ++e) b.force[e] -= mg[e], b.torque[e] -= t[e];
    }
    for (Body& b : set_.bodies)
      for (int e = 0; e < 3; ++e) b.force[e] += b.mass * g[e];
    set_.damp_again();  // fix damping/cundall on the corrected sums
  }
}

void FixMultisphere::add_body(const ClumpShape& shape, const double xcm[3], const Q4& q_ins, const double v[3],
                              const double w[3], std::size_t first) {
  const std::size_t n = shape.displace.size();
  check_integrators(first, n);
  Body b;
  b.mass = shape.mass;
  b.inv_mass = 1.0 / shape.mass;
  for (int k = 0; k < 3; ++k) {
    b.moments[k] = shape.moments[k];
    b.inv_moments[k] = shape.moments[k] > 0 ? 1.0 / shape.moments[k] : 0.0;
    b.xcm[k] = xcm[k];
    b.vcm[k] = v[k];
    b.omega[k] = w[k];
  }
  const std::vector<V3> d = clump_offsets(shape, q_ins, b.q);
  rigid::axes(b.q, b.ex, b.ey, b.ez);
  const V3 wv{w[0], w[1], w[2]};
  const double l[3] = {shape.moments[0] * rigid::dot(wv, b.ex), shape.moments[1] * rigid::dot(wv, b.ey),
                       shape.moments[2] * rigid::dot(wv, b.ez)};
  for (int e = 0; e < 3; ++e) b.angmom[e] = l[0] * b.ex[e] + l[1] * b.ey[e] + l[2] * b.ez[e];
  b.fflag = shape.fflag;
  b.tflag = shape.tflag;
  b.members = static_cast<int>(n);
  set_.bodies.push_back(b);
  const int index = static_cast<int>(set_.bodies.size());
  Atoms& at = sim.atoms;
  pair_col_ = at.add_column("rigid:pair_exclusion", 1);  // first: adding a column may move the others
  at.pair_exclusion = pair_col_;
  auto& pairs = at.column(pair_col_);
  auto& c = at.column(set_.col);
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t i = first + j;
    double* o = &c[BodySet::kStride * i];
    o[0] = index;
    for (int e = 0; e < 3; ++e) o[1 + e] = shape.displace[j][e], o[4 + e] = d[j][e];
    pairs[i] = kExclusionBase + index;
  }
  set_.place_members(true);  // puts every body's members where it is now: none has moved since the last step
}

// A member also moved by a per-atom integrator (nve/sphere) would be integrated twice.
void FixMultisphere::check_integrators(std::size_t first, std::size_t n) const {
  const Atoms& at = sim.atoms;
  for (auto& f : sim.fixes) {
    if (f->role(INITIAL_INTEGRATE) != FixRole::Integrator) continue;
    for (std::size_t i = first; i < first + n; ++i)
      if (at.mask[i] & f->groupbit)
        args.fail_line("a multisphere clump's sphere (atom " + std::to_string(at.id[i]) + ") is also integrated by fix " +
                       f->id + " (" + f->style + "): give that fix a group without the clumps (LIGGGHTS would move "
                       "them twice)");
  }
}

double FixMultisphere::kinetic_energy() const { return set_.translational_energy(); }

double FixMultisphere::rotational_energy() const {
  double e = 0;
  for (const Body& b : set_.bodies) {
    const double w[3] = {rigid::dot(b.omega, b.ex), rigid::dot(b.omega, b.ey), rigid::dot(b.omega, b.ez)};
    for (int k = 0; k < 3; ++k) e += b.moments[k] * w[k] * w[k];
  }
  return 0.5 * e;
}

bool FixMultisphere::write_state(std::string& out) const {
  restart::Packer p;
  p.put_vector(set_.bodies);
  p.put_vector(set_.number);
  out = p.bytes;
  return true;
}

void FixMultisphere::read_state(const std::string& in) {
  restart::Unpacker u(in, "the restart state of fix " + id);
  set_.bodies = u.get_vector<Body>();
  set_.number = u.get_vector<int>();
  set_.numbers_read();
}

SABLE_FIX("multisphere", FixMultisphere);

}  // namespace sable
