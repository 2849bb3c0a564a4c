#pragma once
// Neighbour-list test helpers: a bare scene (atoms, box, neighbour), the pairs
// within ri + rj + skin found by brute force over periodic images, and the
// pairs a built list holds, both as (low id, high id, image shift) sets.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <tuple>

#include "core/engine/atoms.h"
#include "core/engine/domain.h"
#include "core/engine/neighbor.h"

namespace sable::test {

struct Scene {
  Atoms atoms;
  Domain domain;
  Neighbor neighbor;
};

// Pairs (id_lo, id_hi, image shift) within ri + rj + skin, by brute force over images.
inline std::set<std::tuple<long, long, int, int, int>> brute(const Scene& s) {
  std::set<std::tuple<long, long, int, int, int>> out;
  const Atoms& a = s.atoms;
  const Domain& d = s.domain;
  for (std::size_t i = 0; i < a.n; ++i)
    for (std::size_t j = 0; j < a.n; ++j) {
      if (a.id[j] <= a.id[i]) continue;
      for (int sx = -1; sx <= 1; ++sx)
        for (int sy = -1; sy <= 1; ++sy)
          for (int sz = -1; sz <= 1; ++sz) {
            const int sh[3] = {sx, sy, sz};
            bool ok = true;
            double r2 = 0;
            for (int k = 0; k < 3; ++k) {
              if (sh[k] && !d.wraps(k)) ok = false;
              const double dx = a.x[3 * j + k] + sh[k] * d.length(k) - a.x[3 * i + k];
              r2 += dx * dx;
            }
            const double cut = a.radius[i] + a.radius[j] + s.neighbor.skin;
            if (ok && r2 < cut * cut) out.insert({a.id[i], a.id[j], sx, sy, sz});
          }
    }
  return out;
}

inline std::set<std::tuple<long, long, int, int, int>> listed(const Scene& s) {
  std::set<std::tuple<long, long, int, int, int>> out;
  const Atoms& a = s.atoms;
  const NeighborList& l = s.neighbor.list;
  for (std::size_t i = 0; i < a.n; ++i)
    for (int k = l.first[i]; k < l.first[i + 1]; ++k) {
      const int j = l.j[k], c = l.shift[k];
      int sh[3] = {c % 3 - 1, (c / 3) % 3 - 1, c / 9 - 1};
      long ii = a.id[i], jj = a.id[j];
      if (ii > jj) {  // normalise to (low id, high id): the shift flips with the order
        std::swap(ii, jj);
        for (int& v : sh) v = -v;
      }
      EXPECT_TRUE(out.insert({ii, jj, sh[0], sh[1], sh[2]}).second) << "pair listed twice";
    }
  return out;
}

inline void random_moves(Scene& s, unsigned seed, double amp) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amp, amp);
  for (std::size_t i = 0; i < s.atoms.n; ++i)
    for (int k = 0; k < s.domain.dimension; ++k) {
      double& x = s.atoms.x[3 * i + k];
      x += u(rng);
      if (!s.domain.periodic[k]) x = std::clamp(x, s.domain.lo[k], s.domain.hi[k]);
    }
}

}  // namespace sable::test
