#pragma once
// Coarse-graining arithmetic of compute stress/cg (Goldhirsch 2010, Weinhart
// et al. 2012), free of any Simulation so that tests can feed it constructed
// states: the kernels, the line integral along a branch vector, and a regular
// grid of nodes that grains and contacts deposit onto.
//
// Kernels of width w, normalised in 3D (integral over space = 1):
//   lucy:  W = 105/(16 pi w^3) (1 + 3 r/w) (1 - r/w)^3 for r < w (support w);
//   gauss: W = A (exp(-r^2 / (2 s^2)) - exp(-4.5)) for r < 3 s, s = w/2
//          (support 1.5 w): the Gaussian of standard deviation w/2 cut at 3 sd
//          and lowered by its value there, so that W is continuous at the cut,
//          A making the integral 1. Without the shift the jump at the cut
//          (1.1 % of the peak) made a lattice's phi err by 1.6 % at w = 2 d,
//          against 0.3 % with it.
// In 2D (dimension 2) the same shapes are normalised over the plane
// (integral over area = 1), r the distance in the x-y plane:
//   lucy:  W = 5/(pi w^2) (1 + 3 r/w) (1 - r/w)^3;
//   gauss: A = 1 / (pi s^2 (2 - 11 exp(-4.5))), kneib2017 App. C's Gaussian
//          of sd d/2 for w = d, cut and lowered as in 3D.
// So a field is per unit area: phi the area fraction, rho in kg/m^2, the
// stresses in N/m (force per length).
// The line integral int_0^1 W(q + s b) ds is exact (closed form of both
// kernels along a line), not a quadrature: clip the line to the support,
// then the antiderivative in the distance along the line.
#include <cstddef>
#include <string>
#include <vector>

namespace sable {

class CgKernel {
 public:
  enum class Kind { Lucy, Gauss };
  explicit CgKernel(Kind kind = Kind::Lucy, double w = 1, int dimension = 3);
  Kind kind() const { return kind_; }
  double w() const { return w_; }  // width
  int dimension() const { return dim_; }  // 2: normalised over the plane
  double support() const { return kind_ == Kind::Lucy ? w_ : 1.5 * w_; }
  double value(double r) const;  // W(r)
  // int_0^1 W(|q + s b|) ds: the share of a branch b starting at q from the node.
  double line(const double q[3], const double b[3]) const;
  // The same with L = |b| known (a contact's nodes share it).
  double line(const double q[3], const double b[3], double L) const;
  std::string name() const { return kind_ == Kind::Lucy ? "lucy" : "gauss"; }

 private:
  Kind kind_;
  double w_;
  int dim_;
  double norm_;  // the factor making the integral 1
  // int W(sqrt(d2 + u^2)) du from u0 to u1 (both inside the support).
  double along(double d2, double u0, double u1) const;
};

// Nodes at cell centres: x_i = lo + (i + 1/2) (hi - lo) / n per axis, node
// index (i ny + j) nz + k (z fastest: a C array [nx][ny][nz]). With a 2D
// kernel, positions and branches count in the x-y plane only (their z parts
// dropped): every node of a column gets the same values.
// Fields per node, in this order (kNames):
//   rho, phi, u (3), stress (6), stress_contact (6), stress_kinetic (6);
// tensors as the 6 components xx yy zz xy xz yz of the symmetrised tensor.
class CgField {
 public:
  static constexpr int kFields = 23;
  struct Group {
    const char* name;
    int first, count;
  };
  static constexpr Group kGroups[6] = {{"rho", 0, 1},    {"phi", 1, 1},             {"u", 2, 3},
                                       {"stress", 5, 6}, {"stress_contact", 11, 6}, {"stress_kinetic", 17, 6}};

  CgField(const CgKernel& k, const double lo[3], const double hi[3], const int n[3]);
  std::size_t nodes() const { return static_cast<std::size_t>(n_[0]) * n_[1] * n_[2]; }
  double coord(int axis, int i) const { return lo_[axis] + (i + 0.5) * h_[axis]; }
  const int* shape() const { return n_; }
  const CgKernel& kernel() const { return kern_; }

  void clear();
  // A grain at x (grid coordinates) with velocity v, mass m and volume vol (2D: its area).
  void add_grain(const double x[3], const double v[3], double m, double vol);
  // A contact of grain centre x with branch b (from the partner's centre or the
  // wall point to x) and force f on the grain: sym(f (x) b) along the branch.
  void add_contact(const double x[3], const double b[3], const double f[3]);
  // Fields per node (kFields each) from what was added since clear().
  void finish(std::vector<double>& out) const;

 private:
  CgKernel kern_;
  bool plane_;  // a 2D kernel: z dropped
  double lo_[3], h_[3];
  int n_[3];
  // Per node: m W, V W, m v W (3), m v v W (6), contact (6).
  static constexpr int kAcc = 17;
  std::vector<double> acc_;
  // Node index range [i0, i1] per axis whose nodes lie within reach of [a, b]; false if empty.
  bool span(const double a[3], const double b[3], double reach, int i0[3], int i1[3]) const;
};

}  // namespace sable
