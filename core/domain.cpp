#include "core/domain.h"

namespace sable {

bool Domain::inside(const double* x) const {
  for (int k = 0; k < dimension; ++k)
    if (x[k] < lo[k] || x[k] >= hi[k]) return false;
  return true;
}

void Domain::remap(double* x, int* image) const {
  for (int k = 0; k < 3; ++k) {
    if (!wraps(k)) continue;
    const double L = length(k);
    while (x[k] < lo[k]) {
      x[k] += L;
      --image[k];
    }
    while (x[k] >= hi[k]) {
      x[k] -= L;
      ++image[k];
    }
  }
}

void Domain::unmap(const double* x, const int* image, double* out) const {
  for (int k = 0; k < 3; ++k) out[k] = x[k] + image[k] * length(k);
}

double Domain::volume() const {
  double v = length(0) * length(1);
  return dimension == 3 ? v * length(2) : v;
}

}  // namespace sable
