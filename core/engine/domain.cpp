#include "core/engine/domain.h"

#include <cmath>

namespace sable {

bool Domain::inside(const double* x) const {
  for (int k = 0; k < dimension; ++k)
    if (x[k] < lo[k] || x[k] >= hi[k]) return false;
  return true;
}

void Domain::remap(double* x, int* image) const {
  for (int k = 0; k < 3; ++k) {
    if (!wraps(k) || (x[k] >= lo[k] && x[k] < hi[k])) continue;
    const double L = length(k);
    const double n = std::floor((x[k] - lo[k]) / L);  // whole periods to shift (callers check finiteness)
    x[k] -= n * L;
    if (x[k] >= hi[k]) x[k] = lo[k];  // round-off at the upper edge
    image[k] += static_cast<int>(n);
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
