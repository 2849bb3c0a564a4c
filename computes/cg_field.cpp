#include "computes/cg_field.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sable {

namespace {

constexpr double kPi = std::numbers::pi;
const double kGaussCut = std::exp(-4.5);  // the Gaussian at 3 sd, which the kernel subtracts

// Mass of the unit 3D Gaussian inside 3 standard deviations (chi distribution, 3 dof).
double gauss_inside() { return std::erf(3.0 / std::sqrt(2.0)) - std::sqrt(2.0 / kPi) * 3.0 * std::exp(-4.5); }

double lucy_norm(double w) { return 105.0 / (16.0 * kPi * w * w * w); }

// The Gaussian lowered by its value at the cut e^-4.5 (continuous there), over its integral inside.
double gauss_norm(double w) {
  const double s = 0.5 * w;
  return 1.0 / (s * s * s * (std::pow(2.0 * kPi, 1.5) * gauss_inside() - 36.0 * kPi * std::exp(-4.5)));
}

// Over the plane: int 2 pi r (1 + 3t)(1 - t)^3 dr = pi w^2 / 5 (t = r/w), and
// int 2 pi r (exp(-r^2/2s^2) - e^-4.5) dr over r < 3s = pi s^2 (2 (1 - e^-4.5) - 9 e^-4.5).
double lucy_norm_2d(double w) { return 5.0 / (kPi * w * w); }
double gauss_norm_2d(double w) {
  const double s = 0.5 * w;
  return 1.0 / (kPi * s * s * (2.0 - 11.0 * std::exp(-4.5)));
}

double norm(CgKernel::Kind kind, double w, int dim) {
  if (dim == 2) return kind == CgKernel::Kind::Lucy ? lucy_norm_2d(w) : gauss_norm_2d(w);
  return kind == CgKernel::Kind::Lucy ? lucy_norm(w) : gauss_norm(w);
}

// int (d^2 + u^2)^(3/2) du from u0 to u1 (d2 = d^2): the algebraic part
// u (2u^2 + 5d^2) r / 8 at both ends, plus 3 d^4 / 8 (asinh(u1/d) - asinh(u0/d)),
// the latter as one log of (u + r) ratios (u + r = d^2 / (r - u) for u < 0: no cancellation).
double cube_root_integral(double d2, double u0, double u1) {
  const double r0 = std::sqrt(d2 + u0 * u0), r1 = std::sqrt(d2 + u1 * u1);
  double s = (u1 * (2.0 * u1 * u1 + 5.0 * d2) * r1 - u0 * (2.0 * u0 * u0 + 5.0 * d2) * r0) / 8.0;
  if (d2 > 0) {
    auto plus = [&](double u, double r) { return u >= 0 ? u + r : d2 / (r - u); };
    s += 3.0 / 8.0 * d2 * d2 * std::log(plus(u1, r1) / plus(u0, r0));
  }
  return s;
}

}  // namespace

CgKernel::CgKernel(Kind kind, double w, int dimension)
    : kind_(kind), w_(w), dim_(dimension == 2 ? 2 : 3), norm_(norm(kind, w, dim_)) {}

double CgKernel::value(double r) const {
  if (r >= support()) return 0.0;
  if (kind_ == Kind::Lucy) {
    const double t = r / w_, m = 1.0 - t;
    return norm_ * (1.0 + 3.0 * t) * m * m * m;
  }
  const double s = 0.5 * w_;
  return norm_ * (std::exp(-r * r / (2.0 * s * s)) - kGaussCut);
}

double CgKernel::along(double d2, double u0, double u1) const {
  if (kind_ == Kind::Lucy) {
    // W = C (1 - 6 t^2 + 8 t^3 - 3 t^4), t = r / w, r^2 = d^2 + u^2: term by term.
    const double w = w_, w2 = w * w;
    auto G = [&](double u) {  // the polynomial terms' antiderivative
      const double u3 = u * u * u, u5 = u3 * u * u;
      return u - 6.0 / w2 * (d2 * u + u3 / 3.0) - 3.0 / (w2 * w2) * (d2 * d2 * u + 2.0 * d2 * u3 / 3.0 + u5 / 5.0);
    };
    return norm_ * (G(u1) - G(u0) + 8.0 / (w2 * w) * cube_root_integral(d2, u0, u1));
  }
  const double s = 0.5 * w_, k = 1.0 / (s * std::sqrt(2.0));
  return norm_ * (std::exp(-d2 / (2.0 * s * s)) * s * std::sqrt(kPi / 2.0) * (std::erf(u1 * k) - std::erf(u0 * k)) -
                  kGaussCut * (u1 - u0));
}

double CgKernel::line(const double q[3], const double b[3]) const {
  return line(q, b, std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]));
}

double CgKernel::line(const double q[3], const double b[3], double L) const {
  const double R = support();
  if (L < 1e-9 * R) return value(std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]));  // a point, not a line
  // Distance to the node along the line u = s L + a, and across it d (cross product: no cancellation).
  const double a = (q[0] * b[0] + q[1] * b[1] + q[2] * b[2]) / L;
  const double c[3] = {q[1] * b[2] - q[2] * b[1], q[2] * b[0] - q[0] * b[2], q[0] * b[1] - q[1] * b[0]};
  const double d2 = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / (L * L);
  if (d2 >= R * R) return 0.0;
  const double umax = std::sqrt(R * R - d2);
  const double u0 = std::max(a, -umax), u1 = std::min(a + L, umax);
  if (u1 <= u0) return 0.0;
  return along(d2, u0, u1) / L;
}

CgField::CgField(const CgKernel& k, const double lo[3], const double hi[3], const int n[3])
    : kern_(k), plane_(k.dimension() == 2) {
  for (int a = 0; a < 3; ++a) {
    lo_[a] = lo[a];
    n_[a] = n[a];
    h_[a] = (hi[a] - lo[a]) / n[a];
  }
  acc_.assign(nodes() * kAcc, 0.0);
}

void CgField::clear() { std::fill(acc_.begin(), acc_.end(), 0.0); }

bool CgField::span(const double a[3], const double b[3], double reach, int i0[3], int i1[3]) const {
  for (int k = 0; k < (plane_ ? 2 : 3); ++k) {
    // Node i is at lo + (i + 1/2) h; clamp in floating point first (far grains must not overflow an int).
    const double f0 = std::ceil((a[k] - reach - lo_[k]) / h_[k] - 0.5);
    const double f1 = std::floor((b[k] + reach - lo_[k]) / h_[k] - 0.5);
    i0[k] = static_cast<int>(std::clamp(f0, 0.0, static_cast<double>(n_[k])));
    i1[k] = static_cast<int>(std::clamp(f1, -1.0, static_cast<double>(n_[k] - 1)));
    if (i1[k] < i0[k]) return false;
  }
  if (plane_) {  // z does not count in 2D: the whole column
    i0[2] = 0;
    i1[2] = n_[2] - 1;
  }
  return true;
}

void CgField::add_grain(const double x[3], const double v[3], double m, double vol) {
  int i0[3], i1[3];
  const double R = kern_.support();
  if (!span(x, x, R, i0, i1)) return;
  const double mv[3] = {m * v[0], m * v[1], m * v[2]};
  const double mvv[6] = {mv[0] * v[0], mv[1] * v[1], mv[2] * v[2], mv[0] * v[1], mv[0] * v[2], mv[1] * v[2]};
  for (int i = i0[0]; i <= i1[0]; ++i) {
    const double dx = coord(0, i) - x[0];
    for (int j = i0[1]; j <= i1[1]; ++j) {
      const double dy = coord(1, j) - x[1];
      for (int k = i0[2]; k <= i1[2]; ++k) {
        const double dz = plane_ ? 0.0 : coord(2, k) - x[2];
        const double r2 = dx * dx + dy * dy + dz * dz;
        if (r2 >= R * R) continue;
        const double W = kern_.value(std::sqrt(r2));
        double* a = &acc_[((static_cast<std::size_t>(i) * n_[1] + j) * n_[2] + k) * kAcc];
        a[0] += m * W;
        a[1] += vol * W;
        for (int c = 0; c < 3; ++c) a[2 + c] += mv[c] * W;
        for (int c = 0; c < 6; ++c) a[5 + c] += mvv[c] * W;
      }
    }
  }
}

void CgField::add_contact(const double x[3], const double bw[3], const double f[3]) {
  const double b[3] = {bw[0], bw[1], plane_ ? 0.0 : bw[2]};  // 2D: the branch in the plane
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::min(x[k], x[k] - b[k]);
    hi[k] = std::max(x[k], x[k] - b[k]);
  }
  int i0[3], i1[3];
  if (!span(lo, hi, kern_.support(), i0, i1)) return;
  const double fb[6] = {f[0] * b[0], f[1] * b[1], f[2] * b[2], 0.5 * (f[0] * b[1] + f[1] * b[0]),
                        0.5 * (f[0] * b[2] + f[2] * b[0]), 0.5 * (f[1] * b[2] + f[2] * b[1])};
  const double R = kern_.support(), L = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  const double bxy2 = b[0] * b[0] + b[1] * b[1];
  for (int i = i0[0]; i <= i1[0]; ++i)
    for (int j = i0[1]; j <= i1[1]; ++j) {
      // Skip columns farther than R from the branch's shadow in the xy plane (the box's corners).
      const double qx = coord(0, i) - x[0], qy = coord(1, j) - x[1];
      const double t = bxy2 > 0 ? std::clamp(-(qx * b[0] + qy * b[1]) / bxy2, 0.0, 1.0) : 0.0;
      const double ex = qx + t * b[0], ey = qy + t * b[1];
      if (ex * ex + ey * ey >= R * R) continue;
      for (int k = i0[2]; k <= i1[2]; ++k) {
        const double q[3] = {qx, qy, plane_ ? 0.0 : coord(2, k) - x[2]};
        const double s = kern_.line(q, b, L);
        if (s == 0.0) continue;
        double* a = &acc_[((static_cast<std::size_t>(i) * n_[1] + j) * n_[2] + k) * kAcc];
        for (int c = 0; c < 6; ++c) a[11 + c] += fb[c] * s;
      }
    }
}

void CgField::finish(std::vector<double>& out) const {
  out.assign(nodes() * kFields, 0.0);
  for (std::size_t n = 0; n < nodes(); ++n) {
    const double* a = &acc_[n * kAcc];
    double* o = &out[n * kFields];
    const double rho = a[0];
    double u[3] = {0, 0, 0};
    if (rho > 0)
      for (int c = 0; c < 3; ++c) u[c] = a[2 + c] / rho;
    // sum m (v - u)(v - u) W = sum m v v W - rho u u, since sum m v W = rho u.
    const double uu[6] = {u[0] * u[0], u[1] * u[1], u[2] * u[2], u[0] * u[1], u[0] * u[2], u[1] * u[2]};
    o[0] = rho;
    o[1] = a[1];
    for (int c = 0; c < 3; ++c) o[2 + c] = u[c];
    for (int c = 0; c < 6; ++c) {
      o[11 + c] = a[11 + c];
      o[17 + c] = a[5 + c] - rho * uu[c];
      o[5 + c] = o[11 + c] + o[17 + c];
    }
  }
}

}  // namespace sable
