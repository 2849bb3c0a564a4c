// Shared rigid-body machinery; see fixes/rigid_body_set.h.
#include "fixes/rigid_body_set.h"

#include <algorithm>

#include "core/engine/simulation.h"
#include "core/engine/threads.h"
#include "fixes/fix_damping_cundall.h"

namespace sable::rigid {

namespace {

// The small pieces of the orientation step on plain arrays, always inlined: the
// lane loops below are compiled for several vector widths, and GCC inlines a
// function (std::array's operator[] included) into a target-specific one only
// when it is always_inline.
#define SABLE_INLINE [[gnu::always_inline]] inline

SABLE_INLINE void axes_in(const double* q, double* ex, double* ey, double* ez) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  ex[0] = w * w + x * x - y * y - z * z, ex[1] = 2 * (x * y + w * z), ex[2] = 2 * (x * z - w * y);
  ey[0] = 2 * (x * y - w * z), ey[1] = w * w - x * x + y * y - z * z, ey[2] = 2 * (y * z + w * x);
  ez[0] = 2 * (x * z + w * y), ez[1] = 2 * (y * z - w * x), ez[2] = w * w - x * x - y * y + z * z;
}

SABLE_INLINE void normalize_in(double* q) {
  const double s = 1.0 / std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (int c = 0; c < 4; ++c) q[c] *= s;
}

SABLE_INLINE void omega_in(const double* m, const double* ex, const double* ey, const double* ez, const double* inv,
                           double* w) {
  const double a = (m[0] * ex[0] + m[1] * ex[1] + m[2] * ex[2]) * inv[0];
  const double b = (m[0] * ey[0] + m[1] * ey[1] + m[2] * ey[2]) * inv[1];
  const double c = (m[0] * ez[0] + m[1] * ez[1] + m[2] * ez[2]) * inv[2];
  for (int k = 0; k < 3; ++k) w[k] = a * ex[k] + b * ey[k] + c * ez[k];
}

// dq/dt = 1/2 (0, w) q, as the product (0, w) q.
SABLE_INLINE void spin(const double* w, const double* q, double* out) {
  out[0] = -(w[0] * q[1] + w[1] * q[2] + w[2] * q[3]);
  out[1] = q[0] * w[0] + w[1] * q[3] - w[2] * q[2];
  out[2] = q[0] * w[1] + w[2] * q[1] - w[0] * q[3];
  out[3] = q[0] * w[2] + w[0] * q[2] - w[1] * q[1];
}

SABLE_INLINE void step_q(const double* q, const double* wq, double h, double* r) {
  for (int c = 0; c < 4; ++c) r[c] = q[c] + h * wq[c];
  normalize_in(r);
}

// One orientation step of dt = 2 dtq by Richardson extrapolation (LAMMPS' fix rigid):
// a full step and two half steps (omega recomputed from m at the midpoint), combined as 2 half - full.
SABLE_INLINE void richardson(double* q, const double* m, double* w, const double* inv, double dtq) {
  double wq[4], full[4], half[4], half2[4], ex[3], ey[3], ez[3];
  spin(w, q, wq);
  step_q(q, wq, dtq, full);
  step_q(q, wq, 0.5 * dtq, half);
  axes_in(half, ex, ey, ez);
  omega_in(m, ex, ey, ez, inv, w);
  spin(w, half, wq);
  step_q(half, wq, 0.5 * dtq, half2);
  for (int c = 0; c < 4; ++c) q[c] = 2.0 * half2[c] - full[c];
  normalize_in(q);
}

// The orientation step of rigid_body_set.h's initial_integrate for a batch of
// bodies, one array per component: the same operations as body by body, in a
// loop over the lanes that the compiler vectorises (the square roots and
// divisions of the normalisations then overlap; no FMA: the same bits).
constexpr int kLanes = 8;
struct Lanes {
  double q[4][kLanes], m[3][kLanes], inv[3][kLanes], w[3][kLanes], e[9][kLanes];
};

SABLE_INLINE void turn_lane(Lanes& L, int l, double dtq) {
  double q[4], m[3], inv[3], w[3], e[9];
  for (int c = 0; c < 4; ++c) q[c] = L.q[c][l];
  for (int c = 0; c < 3; ++c) m[c] = L.m[c][l], inv[c] = L.inv[c][l];
  for (int c = 0; c < 9; ++c) e[c] = L.e[c][l];
  omega_in(m, e, e + 3, e + 6, inv, w);
  richardson(q, m, w, inv, dtq);
  axes_in(q, e, e + 3, e + 6);
  for (int c = 0; c < 4; ++c) L.q[c][l] = q[c];
  for (int c = 0; c < 3; ++c) L.w[c][l] = w[c];
  for (int c = 0; c < 9; ++c) L.e[c][l] = e[c];
}

[[gnu::flatten]] void turn_lanes(Lanes& L, double dtq) {
  for (int l = 0; l < kLanes; ++l) turn_lane(L, l, dtq);
}
[[gnu::target("avx2"), gnu::flatten]] void turn_lanes_avx2(Lanes& L, double dtq) {
  for (int l = 0; l < kLanes; ++l) turn_lane(L, l, dtq);
}
[[gnu::target("avx512f,avx512dq"), gnu::flatten]] void turn_lanes_avx512(Lanes& L, double dtq) {
  for (int l = 0; l < kLanes; ++l) turn_lane(L, l, dtq);
}

// Turns the bodies listed in idx (at most kLanes; the empty lanes hold a body at rest).
void turn_bodies(std::vector<Body>& bodies, const int* idx, int n, double dtq) {
  Lanes L{};
  for (int l = 0; l < kLanes; ++l) L.q[0][l] = 1.0;
  for (int l = 0; l < n; ++l) {
    const Body& b = bodies[idx[l]];
    for (int c = 0; c < 4; ++c) L.q[c][l] = b.q[c];
    for (int c = 0; c < 3; ++c) {
      L.m[c][l] = b.angmom[c];
      L.inv[c][l] = b.inv_moments[c];
      L.e[c][l] = b.ex[c];
      L.e[3 + c][l] = b.ey[c];
      L.e[6 + c][l] = b.ez[c];
    }
  }
  switch (simd_level()) {
    case Simd::AVX512: turn_lanes_avx512(L, dtq); break;
    case Simd::AVX2: turn_lanes_avx2(L, dtq); break;
    default: turn_lanes(L, dtq);
  }
  for (int l = 0; l < n; ++l) {
    Body& b = bodies[idx[l]];
    for (int c = 0; c < 4; ++c) b.q[c] = L.q[c][l];
    for (int c = 0; c < 3; ++c) {
      b.omega[c] = L.w[c][l];
      b.ex[c] = L.e[c][l];
      b.ey[c] = L.e[3 + c][l];
      b.ez[c] = L.e[6 + c][l];
    }
  }
}

// A body that spins about world z only, with z one of its principal axes (its
// orientation a pure turn about z: q = (w, 0, 0, z), ez = (0, 0, w^2 + z^2)), keeps
// omega = L_z / I_z: its orientation step is that exact turn, without Richardson's iteration.
bool turns_about_z(const Body& b) {
  return b.q[1] == 0 && b.q[2] == 0 && b.angmom[0] == 0 && b.angmom[1] == 0;
}

// The turn about z of a batch of such bodies, in lanes as turn_lanes: omega as
// omega_of gives it for this orientation (the same bits); sin and cos of the half
// angle by their Taylor series to x^7 and x^6 (below round-off for |x| <= 1e-2;
// larger angles are redone with the library's); the turned q brought back to unit
// length by one Newton step (|q|^2 is 1 to round-off: no square root).
struct ZLanes {
  double w[kLanes], z[kLanes], m[kLanes], inv[kLanes], om[kLanes], x[kLanes];
};

SABLE_INLINE void turn_z_lane(ZLanes& L, int l, double dt, bool small) {
  const double w = L.w[l], z = L.z[l], ez = w * w + z * z;
  const double om = L.m[l] * ez * L.inv[l] * ez, x = 0.5 * dt * om, x2 = x * x;
  double s = x * (1 - x2 / 6 * (1 - x2 / 20 * (1 - x2 / 42)));
  double c = 1 - x2 / 2 * (1 - x2 / 12 * (1 - x2 / 30));
  if (!small) s = std::sin(x), c = std::cos(x);
  double qw = c * w - s * z, qz = c * z + s * w;
  const double k = 1.5 - 0.5 * (qw * qw + qz * qz);
  L.w[l] = qw * k, L.z[l] = qz * k, L.om[l] = om, L.x[l] = x;
}

[[gnu::flatten]] void turn_z_lanes(ZLanes& L, double dt) {
  for (int l = 0; l < kLanes; ++l) turn_z_lane(L, l, dt, true);
}
[[gnu::target("avx2"), gnu::flatten]] void turn_z_lanes_avx2(ZLanes& L, double dt) {
  for (int l = 0; l < kLanes; ++l) turn_z_lane(L, l, dt, true);
}
[[gnu::target("avx512f,avx512dq"), gnu::flatten]] void turn_z_lanes_avx512(ZLanes& L, double dt) {
  for (int l = 0; l < kLanes; ++l) turn_z_lane(L, l, dt, true);
}

void turn_bodies_about_z(std::vector<Body>& bodies, const int* idx, int n, double dt) {
  ZLanes L{};
  for (int l = 0; l < kLanes; ++l) L.w[l] = 1.0;
  for (int l = 0; l < n; ++l) {
    const Body& b = bodies[idx[l]];
    L.w[l] = b.q[0], L.z[l] = b.q[3], L.m[l] = b.angmom[2], L.inv[l] = b.inv_moments[2];
  }
  const ZLanes in = L;
  switch (simd_level()) {
    case Simd::AVX512: turn_z_lanes_avx512(L, dt); break;
    case Simd::AVX2: turn_z_lanes_avx2(L, dt); break;
    default: turn_z_lanes(L, dt);
  }
  for (int l = 0; l < n; ++l) {
    if (std::abs(L.x[l]) > 1e-2) {
      ZLanes one = in;
      turn_z_lane(one, l, dt, false);
      L.w[l] = one.w[l], L.z[l] = one.z[l];
    }
    Body& b = bodies[idx[l]];
    b.q = {L.w[l], 0.0, 0.0, L.z[l]};
    b.omega = {0.0, 0.0, L.om[l]};
    axes_in(b.q.data(), b.ex.data(), b.ey.data(), b.ez.data());
  }
}

#undef SABLE_INLINE

}  // namespace

void axes(const Q4& q, V3& ex, V3& ey, V3& ez) { axes_in(q.data(), ex.data(), ey.data(), ez.data()); }
void normalize(Q4& q) { normalize_in(q.data()); }
V3 omega_of(const V3& m, const V3& ex, const V3& ey, const V3& ez, const V3& inv) {
  V3 w;
  omega_in(m.data(), ex.data(), ey.data(), ez.data(), inv.data(), w.data());
  return w;
}

// A body whose inertia has z as an exact principal axis (a planar body, 2D) gets
// the in-plane axes from the x-y block and z itself, so that its orientation is a
// pure turn about z (turns_about_z) for as long as it spins about z alone.
void principal_axes(Body& b, const Eigen::Matrix3d& inertia) {
  Eigen::Matrix3d R;
  Eigen::Vector3d moment;
  if (inertia(0, 2) == 0 && inertia(1, 2) == 0) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(inertia.topLeftCorner<2, 2>().eval());
    R.setZero();
    R.topLeftCorner<2, 2>() = eig.eigenvectors();
    R(2, 2) = 1;
    moment << eig.eigenvalues(), inertia(2, 2);
    if (R.determinant() < 0) R.col(0) = -R.col(0);
  } else {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(inertia);
    R = eig.eigenvectors();
    moment = eig.eigenvalues();
    if (R.determinant() < 0) R.col(2) = -R.col(2);
  }
  const double imax = moment.maxCoeff();
  for (int k = 0; k < 3; ++k) {
    b.moments[k] = moment[k] < 1e-7 * imax ? 0.0 : moment[k];
    b.inv_moments[k] = b.moments[k] > 0 ? 1.0 / b.moments[k] : 0.0;
  }
  const Eigen::Quaterniond q(R);
  b.q = {q.w(), q.x(), q.y(), q.z()};
  normalize(b.q);
  axes(b.q, b.ex, b.ey, b.ez);
}

int BodySet::body_of_atom(std::size_t i) const {
  return col < 0 || i >= sim_.atoms.n ? -1 : static_cast<int>(sim_.atoms.column(col)[kStride * i]) - 1;
}

bool BodySet::any_rotates() const { return std::any_of(bodies.begin(), bodies.end(), rotates); }

double BodySet::translational_energy() const {
  double e = 0;
  for (const Body& b : bodies) e += b.mass * dot(b.vcm, b.vcm);
  return 0.5 * e;
}

bool BodySet::body_kinetic_energy(double& ke) const {
  if (members_carry_mass) ke = translational_energy();
  return members_carry_mass;
}

namespace {
void kick(Body& b, double dtf) {
  for (int k = 0; k < 3; ++k) {
    // (undamped: the sums alone, bit for bit)
    if (b.fflag[k]) b.vcm[k] += dtf * (b.fdamp[k] == 0.0 ? b.force[k] : b.force[k] + b.fdamp[k]) * b.inv_mass;
    if (b.tflag[k]) b.angmom[k] += dtf * (b.tdamp[k] == 0.0 ? b.torque[k] : b.torque[k] + b.tdamp[k]);
  }
}

// The second half kick; with `spin`, omega for the members' velocities (the next
// orientation step recomputes it from the angular momentum anyway).
void second_half(Body& b, double dt, bool spin) {
  kick(b, 0.5 * dt);
  if (spin && BodySet::rotates(b)) b.omega = omega_of(b.angmom, b.ex, b.ey, b.ez, b.inv_moments);
}
}  // namespace

// Bodies k0 .. k1 - 1: the first half kick, the drift, the turn.
void BodySet::advance(int k0, int k1, double dt) {
  const double dtf = 0.5 * dt;
  for (int k = k0; k < k1; ++k) {
    Body& b = bodies[k];
    kick(b, dtf);
    for (int e = 0; e < 3; ++e) b.xcm[e] += dt * b.vcm[e];
  }
  turn(k0, k1, dt);
}

void BodySet::turn(int k0, int k1, double dt) {
  int idx[kLanes], zidx[kLanes], n = 0, nz = 0;
  for (int k = k0; k < k1; ++k) {
    turning_[k] = rotates(bodies[k]);
    if (!turning_[k]) continue;
    if (turns_about_z(bodies[k])) {
      zidx[nz++] = k;
      if (nz == kLanes) turn_bodies_about_z(bodies, zidx, nz, dt), nz = 0;
      continue;
    }
    idx[n++] = k;
    if (n == kLanes) turn_bodies(bodies, idx, n, 0.5 * dt), n = 0;
  }
  if (n > 0) turn_bodies(bodies, idx, n, 0.5 * dt);
  if (nz > 0) turn_bodies_about_z(bodies, zidx, nz, dt);
}

void BodySet::initial_integrate(double dt) {
  turning_.resize(bodies.size());
  advance(0, static_cast<int>(bodies.size()), dt);
  place_range(0, sim_.atoms.n, true);
}

void BodySet::final_integrate(double dt) {
  for (Body& b : bodies) second_half(b, dt, true);
  place_members(false);
}

void BodySet::begin_task() {
  follow_atom_order();
  turning_.resize(bodies.size());
}

void BodySet::owned(const Fix::AtomRange& r, int& k0, int& k1) const {
  k0 = static_cast<int>(std::lower_bound(first_.begin(), first_.end(), r.lo) - first_.begin());
  k1 = r.hi >= sim_.atoms.n ? static_cast<int>(bodies.size())
                            : static_cast<int>(std::lower_bound(first_.begin(), first_.end(), r.hi) - first_.begin());
}

void BodySet::initial_range(const Fix::AtomRange& r, double dt) {
  if (r.phase == 0) {
    int k0, k1;
    owned(r, k0, k1);
    advance(k0, k1, dt);
    return;
  }
  place_range(r.lo, r.hi, true);
}

void BodySet::final_range(const Fix::AtomRange& r, double dt) {
  if (r.phase == 1) return place_range(r.lo, r.hi, false);
  int k0, k1;
  owned(r, k0, k1);
  for (int k = k0; k < k1; ++k) {
    sum_body(k);
    second_half(bodies[k], dt, true);
  }
}

void BodySet::expected(std::size_t i, int k, double* x, double* v) const {
  const Body& b = bodies[k];
  const double* o = &sim_.atoms.column(col)[kStride * i];
  const V3 d{o[4], o[5], o[6]};
  const V3 wd = cross(b.omega, d);
  int image[3] = {0, 0, 0};
  for (int e = 0; e < 3; ++e) {
    x[e] = b.xcm[e] + d[e];
    v[e] = b.vcm[e] + wd[e];
  }
  sim_.domain.remap(x, image);
}

namespace {
// Bodies are met in the atoms' (spatial) order: fetch the body of the atom kAhead
// places on while this one is placed (its first three lines: the fields read).
constexpr std::size_t kAhead = 8;
void prefetch_body(const std::vector<Body>& bodies, const std::vector<double>& c, std::size_t i, std::size_t n) {
  if (i + kAhead >= n) return;
  const int k = static_cast<int>(c[BodySet::kStride * (i + kAhead)]) - 1;
  if (k < 0) return;
  const char* p = reinterpret_cast<const char*>(&bodies[k]);
  __builtin_prefetch(p);
  __builtin_prefetch(p + 64);
  __builtin_prefetch(p + 128);
}
}  // namespace

void BodySet::place_members(bool positions) {
  if (positions) {
    turning_.resize(bodies.size());
    for (std::size_t k = 0; k < bodies.size(); ++k) turning_[k] = rotates(bodies[k]);
  }
  place_range(0, sim_.atoms.n, positions);
}

// With positions, turning_ holds rotates() of each body as it is now.
void BodySet::place_range(std::size_t lo, std::size_t hi, bool positions) {
  const Domain& dom = sim_.domain;
  const bool wrap = dom.wraps(0) || dom.wraps(1) || dom.wraps(2);
  Atoms& at = sim_.atoms;
  auto& c = at.column(col);
  for (std::size_t i = lo; i < hi; ++i) {
    prefetch_body(bodies, c, i, hi);
    const int k = static_cast<int>(c[kStride * i]) - 1;
    if (k < 0) continue;
    const Body& b = bodies[k];
    double* o = &c[kStride * i];
    if (positions && turning_[k])
      for (int e = 0; e < 3; ++e) o[4 + e] = o[1] * b.ex[e] + o[2] * b.ey[e] + o[3] * b.ez[e];
    const V3 d{o[4], o[5], o[6]};
    const V3 wd = cross(b.omega, d);
    double* x = &at.x[3 * i];
    bool inside = true;
    for (int e = 0; e < 3; ++e) {
      if (positions) {
        at.image[3 * i + e] = 0;
        x[e] = b.xcm[e] + d[e];
        inside = inside && x[e] >= dom.lo[e] && x[e] < dom.hi[e];
      }
      at.v[3 * i + e] = b.vcm[e] + wd[e];
      at.omega[3 * i + e] = b.omega[e];
    }
    if (positions && wrap && !inside) dom.remap(x, &at.image[3 * i]);
  }
}

// A body appended since the last look (an insertion, a definition) takes the next number.
void BodySet::number_new_bodies() {
  for (std::size_t k = number.size(); k < bodies.size(); ++k) {
    number.push_back(static_cast<int>(k));
    slot_.push_back(static_cast<int>(k));
  }
}

void BodySet::numbers_read() {
  slot_.assign(number.size(), 0);
  for (std::size_t k = 0; k < number.size(); ++k) slot_[number[k]] = static_cast<int>(k);
  number_new_bodies();
}

// Only the order of the bodies changes: each body's sums still run over its
// members in atom order, so the bits are those of any other numbering.
void BodySet::follow_atom_order() {
  number_new_bodies();
  Atoms& at = sim_.atoms;
  if (sim_.neighbor.builds == builds_seen_ && at.n == atoms_seen_ && bodies.size() == bodies_seen_) return;
  builds_seen_ = sim_.neighbor.builds;
  atoms_seen_ = at.n;
  bodies_seen_ = bodies.size();
  auto& c = at.column(col);
  new_index_.assign(bodies.size(), -1);
  scratch_.clear();
  std::vector<int> renumbered;
  renumbered.reserve(bodies.size());
  auto take = [&](int k) {
    new_index_[k] = static_cast<int>(scratch_.size());
    scratch_.push_back(bodies[k]);
    renumbered.push_back(number[k]);
  };
  for (std::size_t i = 0; i < at.n; ++i)
    if (const int k = static_cast<int>(c[kStride * i]) - 1; k >= 0 && new_index_[k] < 0) take(k);
  for (std::size_t k = 0; k < bodies.size(); ++k)
    if (new_index_[k] < 0) take(static_cast<int>(k));
  for (std::size_t i = 0; i < at.n; ++i)
    if (const int k = static_cast<int>(c[kStride * i]) - 1; k >= 0) c[kStride * i] = new_index_[k] + 1;
  bodies.swap(scratch_);
  number.swap(renumbered);
  for (std::size_t k = 0; k < number.size(); ++k) slot_[number[k]] = static_cast<int>(k);
  list_members();
}

void BodySet::list_members() {
  const Atoms& at = sim_.atoms;
  const auto& c = at.column(col);
  const std::size_t nb = bodies.size();
  start_.assign(nb + 1, 0);
  first_.assign(nb, at.n);
  for (std::size_t i = 0; i < at.n; ++i)
    if (const int k = static_cast<int>(c[kStride * i]) - 1; k >= 0) {
      if (start_[k + 1]++ == 0) first_[k] = i;
    }
  for (std::size_t k = 0; k < nb; ++k) start_[k + 1] += start_[k];
  member_.resize(start_[nb]);
  std::vector<int> at_k(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < at.n; ++i)
    if (const int k = static_cast<int>(c[kStride * i]) - 1; k >= 0) member_[at_k[k]++] = static_cast<int>(i);
}

// Over the members in atom order.
void BodySet::sum_body(int k) {
  const Atoms& at = sim_.atoms;
  const auto& c = at.column(col);
  Body& b = bodies[k];
  b.force = b.torque = V3{0, 0, 0};
  std::uint32_t mask = 0;
  for (int m = start_[k]; m < start_[k + 1]; ++m) {
    const std::size_t i = static_cast<std::size_t>(member_[m]);
    mask |= at.mask[i];
    const V3 f{at.f[3 * i], at.f[3 * i + 1], at.f[3 * i + 2]};
    const V3 d{c[kStride * i + 4], c[kStride * i + 5], c[kStride * i + 6]};
    const V3 t = cross(d, f);
    for (int e = 0; e < 3; ++e) {
      b.force[e] += f[e];
      b.torque[e] += t[e] + at.torque[3 * i + e];
    }
  }
  damp(b, mask);
}

// fix damping/cundall's law (YADE's cundallDamp2nd, as for a clump) on the
// summed force against vcm + dt/2 F/M and the summed torque against
// omega + dt/2 I^-1 T, component by component in the box frame.
void BodySet::damp(Body& b, std::uint32_t mask) const {
  b.fdamp = b.tdamp = V3{0, 0, 0};
  if (damping.empty()) return;
  const double h = 0.5 * sim_.dt;
  V3 f = b.force, t = b.torque;
  const V3 w = omega_of(b.angmom, b.ex, b.ey, b.ez, b.inv_moments);
  for (const Damping& d : damping) {
    if (!(mask & d.groupbit)) continue;
    const V3 dw = omega_of(t, b.ex, b.ey, b.ez, b.inv_moments);
    for (int e = 0; e < 3; ++e) {
      const double df = FixDampingCundall::law(d.alpha, f[e], b.vcm[e] + h * f[e] * b.inv_mass);
      const double dq = FixDampingCundall::law(d.alpha, t[e], w[e] + h * dw[e]);
      f[e] += df, t[e] += dq;
      b.fdamp[e] += df, b.tdamp[e] += dq;
    }
  }
}

void BodySet::damp_again() {
  if (damping.empty()) return;
  const Atoms& at = sim_.atoms;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    std::uint32_t mask = 0;
    for (int m = start_[k]; m < start_[k + 1]; ++m) mask |= at.mask[member_[m]];
    damp(bodies[k], mask);
  }
}

void BodySet::find_damping() {
  damping.clear();
  for (auto& f : sim_.fixes)
    if (const auto* d = dynamic_cast<const FixDampingCundall*>(f.get())) damping.push_back({d->groupbit, d->alpha()});
}

void BodySet::sum_forces() {
  follow_atom_order();
  for (std::size_t k = 0; k < bodies.size(); ++k) sum_body(static_cast<int>(k));
}

}  // namespace sable::rigid
