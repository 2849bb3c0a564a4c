// Shared rigid-body machinery; see fixes/rigid_body_set.h.
#include "fixes/rigid_body_set.h"

#include <algorithm>

#include "core/simulation.h"

namespace sable::rigid {

namespace {

// dq/dt = 1/2 (0, w) q, as the product (0, w) q.
Q4 spin(const V3& w, const Q4& q) {
  return {-(w[0] * q[1] + w[1] * q[2] + w[2] * q[3]), q[0] * w[0] + w[1] * q[3] - w[2] * q[2],
          q[0] * w[1] + w[2] * q[1] - w[0] * q[3], q[0] * w[2] + w[0] * q[2] - w[1] * q[1]};
}

Q4 step_q(const Q4& q, const Q4& wq, double h) {
  Q4 r;
  for (int c = 0; c < 4; ++c) r[c] = q[c] + h * wq[c];
  normalize(r);
  return r;
}

// One orientation step of dt = 2 dtq by Richardson extrapolation (LAMMPS' fix rigid):
// a full step and two half steps (omega recomputed from m at the midpoint), combined as 2 half - full.
void richardson(Q4& q, const V3& m, V3& w, const V3& inv, double dtq) {
  const Q4 wq = spin(w, q);
  const Q4 full = step_q(q, wq, dtq);
  Q4 half = step_q(q, wq, 0.5 * dtq);
  V3 ex, ey, ez;
  axes(half, ex, ey, ez);
  w = omega_of(m, ex, ey, ez, inv);
  half = step_q(half, spin(w, half), 0.5 * dtq);
  for (int c = 0; c < 4; ++c) q[c] = 2.0 * half[c] - full[c];
  normalize(q);
}

}  // namespace

void axes(const Q4& q, V3& ex, V3& ey, V3& ez) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  ex = {w * w + x * x - y * y - z * z, 2 * (x * y + w * z), 2 * (x * z - w * y)};
  ey = {2 * (x * y - w * z), w * w - x * x + y * y - z * z, 2 * (y * z + w * x)};
  ez = {2 * (x * z + w * y), 2 * (y * z - w * x), w * w - x * x - y * y + z * z};
}

void normalize(Q4& q) {
  const double s = 1.0 / std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c *= s;
}

V3 omega_of(const V3& m, const V3& ex, const V3& ey, const V3& ez, const V3& inv) {
  const double a = dot(m, ex) * inv[0], b = dot(m, ey) * inv[1], c = dot(m, ez) * inv[2];
  return {a * ex[0] + b * ey[0] + c * ez[0], a * ex[1] + b * ey[1] + c * ez[1], a * ex[2] + b * ey[2] + c * ez[2]};
}

void principal_axes(Body& b, const Eigen::Matrix3d& inertia) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(inertia);
  Eigen::Matrix3d R = eig.eigenvectors();
  if (R.determinant() < 0) R.col(2) = -R.col(2);
  const double imax = eig.eigenvalues().maxCoeff();
  for (int k = 0; k < 3; ++k) {
    b.moments[k] = eig.eigenvalues()[k] < 1e-7 * imax ? 0.0 : eig.eigenvalues()[k];
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

void BodySet::initial_integrate(double dt) {
  const double dtf = 0.5 * dt;
  for (Body& b : bodies) {
    for (int k = 0; k < 3; ++k) {
      if (b.fflag[k]) b.vcm[k] += dtf * b.force[k] * b.inv_mass;
      b.xcm[k] += dt * b.vcm[k];
      if (b.tflag[k]) b.angmom[k] += dtf * b.torque[k];
    }
    if (rotates(b)) {
      b.omega = omega_of(b.angmom, b.ex, b.ey, b.ez, b.inv_moments);
      richardson(b.q, b.angmom, b.omega, b.inv_moments, 0.5 * dt);
      axes(b.q, b.ex, b.ey, b.ez);
    }
  }
  place_members(true);
}

void BodySet::final_integrate(double dt) {
  const double dtf = 0.5 * dt;
  for (Body& b : bodies) {
    for (int k = 0; k < 3; ++k) {
      if (b.fflag[k]) b.vcm[k] += dtf * b.force[k] * b.inv_mass;
      if (b.tflag[k]) b.angmom[k] += dtf * b.torque[k];
    }
    if (rotates(b)) b.omega = omega_of(b.angmom, b.ex, b.ey, b.ez, b.inv_moments);
  }
  place_members(false);
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

void BodySet::place_members(bool positions) {
  Atoms& at = sim_.atoms;
  auto& c = at.column(col);
  const Domain& dom = sim_.domain;
  const bool wrap = dom.wraps(0) || dom.wraps(1) || dom.wraps(2);
  for (std::size_t i = 0; i < at.n; ++i) {
    const int k = static_cast<int>(c[kStride * i]) - 1;
    if (k < 0) continue;
    const Body& b = bodies[k];
    double* o = &c[kStride * i];
    if (positions && rotates(b))
      for (int e = 0; e < 3; ++e) o[4 + e] = o[1] * b.ex[e] + o[2] * b.ey[e] + o[3] * b.ez[e];
    const V3 d{o[4], o[5], o[6]};
    const V3 wd = cross(b.omega, d);
    for (int e = 0; e < 3; ++e) {
      if (positions) {
        at.image[3 * i + e] = 0;
        at.x[3 * i + e] = b.xcm[e] + d[e];
      }
      at.v[3 * i + e] = b.vcm[e] + wd[e];
      at.omega[3 * i + e] = b.omega[e];
    }
    if (positions && wrap) dom.remap(&at.x[3 * i], &at.image[3 * i]);
  }
}

void BodySet::sum_forces() {
  Atoms& at = sim_.atoms;
  const auto& c = at.column(col);
  for (Body& b : bodies) b.force = b.torque = V3{0, 0, 0};
  for (std::size_t i = 0; i < at.n; ++i) {
    const int k = static_cast<int>(c[kStride * i]) - 1;
    if (k < 0) continue;
    Body& b = bodies[k];
    const V3 f{at.f[3 * i], at.f[3 * i + 1], at.f[3 * i + 2]};
    const V3 d{c[kStride * i + 4], c[kStride * i + 5], c[kStride * i + 6]};
    const V3 t = cross(d, f);
    for (int e = 0; e < 3; ++e) {
      b.force[e] += f[e];
      b.torque[e] += t[e] + at.torque[3 * i + e];
    }
  }
}

}  // namespace sable::rigid
