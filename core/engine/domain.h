#pragma once
// The simulation box: bounds, periodicity per axis, dimension.
namespace sable {

class Domain {
 public:
  bool box_exists = false;
  int dimension = 3;
  bool periodic[3] = {false, false, false};
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};

  double length(int k) const { return hi[k] - lo[k]; }
  // Periodic axes that wrap in this dimension (z never wraps in 2D).
  bool wraps(int k) const { return periodic[k] && k < dimension; }
  bool inside(const double* x) const;
  // Wrap x into the box on periodic axes, updating image counters.
  void remap(double* x, int* image) const;
  // Unwrapped coordinate.
  void unmap(const double* x, const int* image, double* out) const;
  double volume() const;
};

}  // namespace sable
