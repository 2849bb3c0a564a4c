// sable_neighbor_probe: what one neighbour-list build costs on a given packing.
//
//   sable_neighbor_probe DUMP SKIN [BUILDS]
//
// DUMP is a `write_dump ... custom` file with columns id type radius x y z
// (the bench decks' final dumps; box bounds and periodicity from its header).
// Builds the half list BUILDS times (default 50) on one thread, without
// contact history, and prints: atoms, radius range, cutoff (2 rmax + skin),
// bins, the pairs tested per atom (the atoms in the half stencil of its bin),
// list entries per atom, and the median CPU time of a build (thread CPU
// clock, so a busy machine inflates it less than wall time) per atom.
// Written for issue 22 item 5: does a wide size ratio (bins sized by the
// largest grain) make the list build costly? See history.md.
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "core/engine/atoms.h"
#include "core/engine/domain.h"
#include "core/engine/neighbor.h"

using namespace sable;

namespace {

double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

bool read_dump(const char* path, Atoms& atoms, Domain& domain) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("ITEM: BOX BOUNDS", 0) == 0) {
      std::istringstream w(line.substr(16));
      for (int k = 0; k < 3; ++k) {
        std::string b;
        w >> b;
        domain.periodic[k] = b == "pp";
      }
      for (int k = 0; k < 3; ++k) in >> domain.lo[k] >> domain.hi[k];
    } else if (line.rfind("ITEM: ATOMS", 0) == 0) {
      long id;
      int type;
      double r, x[3];
      while (in >> id >> type >> r >> x[0] >> x[1] >> x[2]) {
        atoms.add(id, type, x, r, 2500.0);
        std::getline(in, line);  // the other columns
      }
    }
  }
  return atoms.n > 0;
}

// Pairs the build tests: for each atom, the atoms of the bins of its half
// stencil (sorted build: its own bin's later atoms and 13 of the 26 around),
// with the bin rule of Neighbor::build (bins at least one cutoff wide).
double tested_per_atom(const Atoms& a, const Domain& d, double cutoff) {
  int nb[3];
  for (int k = 0; k < 3; ++k) nb[k] = std::max(1, static_cast<int>(d.length(k) / cutoff));
  std::vector<long> count(static_cast<std::size_t>(nb[0]) * nb[1] * nb[2], 0);
  auto cell = [&](const double* x, int k) {
    return std::clamp(static_cast<int>((x[k] - d.lo[k]) / d.length(k) * nb[k]), 0, nb[k] - 1);
  };
  auto index = [&](int cx, int cy, int cz) { return (static_cast<std::size_t>(cz) * nb[1] + cy) * nb[0] + cx; };
  for (std::size_t i = 0; i < a.n; ++i) ++count[index(cell(&a.x[3 * i], 0), cell(&a.x[3 * i], 1), cell(&a.x[3 * i], 2))];
  double total = 0.0;
  for (int cz = 0; cz < nb[2]; ++cz)
    for (int cy = 0; cy < nb[1]; ++cy)
      for (int cx = 0; cx < nb[0]; ++cx) {
        const double own = count[index(cx, cy, cz)];
        double around = 0.0;
        for (int oz = -1; oz <= 1; ++oz)
          for (int oy = -1; oy <= 1; ++oy)
            for (int ox = -1; ox <= 1; ++ox) {
              if (!ox && !oy && !oz) continue;
              const int c[3] = {cx + ox, cy + oy, cz + oz};
              int w[3];
              bool ok = true;
              for (int k = 0; k < 3; ++k) {
                w[k] = c[k];
                if (c[k] < 0 || c[k] >= nb[k]) {
                  if (!d.periodic[k]) ok = false;
                  w[k] = (c[k] + nb[k]) % nb[k];
                }
              }
              if (ok) around += count[index(w[0], w[1], w[2])];
            }
        total += own * (own - 1) / 2 + own * around / 2;  // each pair of bins once
      }
  return total / a.n;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: sable_neighbor_probe DUMP SKIN [BUILDS]\n");
    return 2;
  }
  Atoms atoms;
  Domain domain;
  if (!read_dump(argv[1], atoms, domain)) {
    std::fprintf(stderr, "no atoms read from %s\n", argv[1]);
    return 1;
  }
  Neighbor nb;
  nb.skin = std::atof(argv[2]);
  const int builds = argc > 3 ? std::atoi(argv[3]) : 50;
  std::vector<double> t;
  for (int b = 0; b < builds; ++b) {
    const double t0 = cpu_seconds();
    nb.build(atoms, domain, nullptr, b);
    t.push_back(cpu_seconds() - t0);
  }
  std::sort(t.begin(), t.end());
  const auto [rmin, rmax] = std::minmax_element(atoms.radius.begin(), atoms.radius.end());
  std::printf("neighbor_probe: atoms %zu radius %.4g..%.4g cutoff %.4g tested/atom %.2f entries/atom %.3f "
              "build_cpu_us/atom %.4f (median of %d)\n",
              atoms.n, *rmin, *rmax, nb.cutoff(), tested_per_atom(atoms, domain, nb.cutoff()),
              static_cast<double>(nb.list.size()) / atoms.n, 1e6 * t[t.size() / 2] / atoms.n, builds);
  return 0;
}
