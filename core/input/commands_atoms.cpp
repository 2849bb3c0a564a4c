// Commands that create atoms: lattice, create_atoms.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/engine/error.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"

namespace sable {
namespace {

// lattice sc|bcc|fcc|sq|sq2|hex|none scale [origin x y z]: scale is the lattice constant (SI units).
void cmd_lattice(Simulation& sim, const Args& a) {
  const std::string& style = a.word(1, "a lattice style: none, sc, bcc, fcc, sq, sq2, hex");
  Lattice& L = sim.lattice;
  L.basis.clear();
  if (style == "none") {
    L.style = "none";
    L.a[0] = L.a[1] = L.a[2] = a.size() > 2 ? a.num(2, "a scale") : 1.0;
    return;
  }
  const double s = a.num(2, "the lattice constant (m)");
  if (!(s > 0)) a.fail(2, "a lattice constant > 0");
  const bool two_d = sim.domain.dimension == 2;
  if ((style == "sq" || style == "sq2" || style == "hex") != two_d)
    a.fail(1, two_d ? "a 2D lattice (sq, sq2, hex) for dimension 2" : "a 3D lattice (sc, bcc, fcc) for dimension 3");
  L.a[0] = L.a[1] = L.a[2] = s;
  if (style == "sc" || style == "sq") L.basis = {{0, 0, 0}};
  else if (style == "bcc" || style == "sq2") L.basis = {{0, 0, 0}, {0.5, 0.5, two_d ? 0.0 : 0.5}};
  else if (style == "fcc") L.basis = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  else if (style == "hex") {
    L.a[1] = s * std::sqrt(3.0);
    L.basis = {{0, 0, 0}, {0.5, 0.5, 0}};
  } else {
    a.fail(1, "a lattice style: none, sc, bcc, fcc, sq, sq2, hex");
  }
  if (two_d) L.a[2] = s;
  L.style = style;
  // origin x y z (LAMMPS): shifts every basis site by these fractions of the lattice spacings
  for (std::size_t i = 3; i < a.size(); i += 4) {
    if (a[i] != "origin") a.fail(i, "'origin' or nothing (orient and spacing are not supported)");
    for (int k = 0; k < 3; ++k) {
      const double o = a.num(i + 1 + k, "an origin fraction in [0, 1)");
      if (!(o >= 0.0 && o < 1.0)) a.fail(i + 1 + k, "an origin fraction in [0, 1)");
      if (two_d && k == 2 && o != 0.0) a.fail(i + 3, "origin z = 0 in 2D");
      for (auto& b : L.basis) b[k] += o;
    }
  }
}

// Per-atom arrays (Atoms, neighbour bins and lists, contact history) take roughly this
// much; only used to refuse a create_atoms that cannot fit, so a generous round number.
constexpr double kBytesPerAtom = 1000.0;

static double physical_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? static_cast<double>(pages) * static_cast<double>(size) : 8e9;
}

void create_on_lattice(Simulation& sim, const Args& a, int type, const Region* region) {
  const Lattice& L = sim.lattice;
  if (L.style == "none") a.fail(1, "a lattice defined before 'create_atoms ... box|region' (use the lattice command)");
  const Domain& d = sim.domain;
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) {
    lo[k] = d.lo[k];
    hi[k] = d.hi[k];
    if (region) {
      lo[k] = std::max(lo[k], region->lo[k]);
      hi[k] = std::min(hi[k], region->hi[k]);
    }
  }
  // Count the sites first (in doubles: a tiny lattice constant overflows a long) so that a
  // deck asking for more atoms than memory holds stops here with the count, not in bad_alloc.
  double sites = static_cast<double>(L.basis.size());
  for (int k = 0; k < d.dimension; ++k) sites *= std::max(1.0, std::ceil(hi[k] / L.a[k]) - std::floor(lo[k] / L.a[k]) + 3);
  const double bytes = sites * kBytesPerAtom, avail = physical_memory_bytes();
  if (bytes > 0.5 * avail) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "create_atoms would make up to %.3g atoms (about %.3g GB of memory) but this machine has %.3g GB: "
                  "use a larger lattice constant or a smaller region",
                  sites, bytes / 1e9, avail / 1e9);
    a.fail_line(buf);
  }
  long n0[3], n1[3];
  for (int k = 0; k < 3; ++k) {
    n0[k] = static_cast<long>(std::floor(lo[k] / L.a[k])) - 1;
    n1[k] = static_cast<long>(std::ceil(hi[k] / L.a[k])) + 1;
  }
  if (d.dimension == 2) n0[2] = n1[2] = 0;
  const double r = 0.5, rho = 1.0;  // LIGGGHTS defaults: diameter 1, density 1 (set them with `set`)
  for (long kz = n0[2]; kz <= n1[2]; ++kz)
    for (long ky = n0[1]; ky <= n1[1]; ++ky)
      for (long kx = n0[0]; kx <= n1[0]; ++kx)
        for (auto& b : L.basis) {
          double x[3] = {(kx + b[0]) * L.a[0], (ky + b[1]) * L.a[1], (kz + b[2]) * L.a[2]};
          if (d.dimension == 2) x[2] = 0.0;
          bool in = true;
          for (int k = 0; k < d.dimension; ++k)
            if (x[k] < d.lo[k] || x[k] >= d.hi[k]) in = false;
          if (!in || (region && !region->match(x))) continue;
          sim.atoms.add(sim.atoms.max_id + 1, type, x, r, rho);
        }
}

// create_atoms type single x y z | box | region ID  [units box|lattice]
void cmd_create_atoms(Simulation& sim, const Args& a) {
  if (!sim.domain.box_exists) a.fail(0, "a box first (create_box before create_atoms)");
  const long type = a.integer(1, "an atom type");
  if (type < 1 || type > sim.atoms.ntypes)
    a.fail(1, "an atom type between 1 and " + std::to_string(sim.atoms.ntypes) + " (create_box set the number of types)");
  const std::string& style = a.word(2, "single, box or region");
  std::size_t next = 3;
  if (style == "single") {
    double x[3];
    for (int k = 0; k < 3; ++k) x[k] = a.num(3 + k, "a coordinate");
    next = 6;
    bool lattice_units = sim.lattice.style != "none";
    for (std::size_t i = next; i < a.size(); i += 2) {
      if (a[i] != "units") a.fail(i, "'units box' or 'units lattice'");
      lattice_units = a.choice(i + 1, {"box", "lattice"}) == 1 && sim.lattice.style != "none";
    }
    if (lattice_units)
      for (int k = 0; k < 3; ++k) x[k] *= sim.lattice.a[k];
    const Domain& d = sim.domain;
    for (int k = 0; k < 3; ++k) {
      const bool out = d.dimension == 2 && k == 2 ? false : (x[k] < d.lo[k] || x[k] > d.hi[k]);
      if (out) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "a point inside the box (%c = %g is outside %g .. %g)", 'x' + k, x[k], d.lo[k], d.hi[k]);
        a.fail(3 + k, buf);
      }
    }
    sim.atoms.add(sim.atoms.max_id + 1, static_cast<int>(type), x, 0.5, 1.0);
  } else if (style == "box") {
    create_on_lattice(sim, a, static_cast<int>(type), nullptr);
  } else if (style == "region") {
    const Region* r = sim.find_region(a.word(3, "a region ID"));
    if (!r) a.fail(3, "an existing region ID");
    create_on_lattice(sim, a, static_cast<int>(type), r);
  } else {
    a.fail(2, "single, box or region");
  }
}

}  // namespace

SABLE_COMMAND("lattice", cmd_lattice);
SABLE_COMMAND("create_atoms", cmd_create_atoms);

}  // namespace sable
