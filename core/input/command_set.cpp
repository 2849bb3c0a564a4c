// set atom|type|group|region ID  keyword value ...   (LIGGGHTS 3.8 `set`)
// Keywords: type, type/fraction, x, y, z, vx, vy, vz, omegax, omegay, omegaz,
// diameter, density, mass, image, property/atom NAME v (a fix's per-atom
// value). Atoms are selected once, then each keyword is applied in order. As
// in LIGGGHTS, diameter and density also set the mass (4/3 pi r^3 rho, or
// pi r^2 rho in 2D); mass sets the mass alone. Values may
// be v_name (atom- or equal-style variable). A single atom ID that does not
// exist is an error (LIGGGHTS would silently make 0 settings).
#include <cmath>
#include <limits>

#include "core/engine/error.h"
#include "core/input/expression.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/input/variable.h"
#include "core/engine/random.h"

namespace sable {
namespace {

// LAMMPS bounds: N, *, N*, *N, M*N within [1, nmax]; `single` tells that no '*' was used.
void star_bounds(const Args& a, std::size_t i, long nmax, long& lo, long& hi, bool& single, const std::string& what) {
  const std::string& w = a.word(i, what);
  const std::string expect = what + " (N, *, N*, *N or M*N)";
  const auto star = w.find('*');
  single = star == std::string::npos;
  auto parse = [&](const std::string& s, long dflt) {
    if (s.empty()) return dflt;
    long v;
    if (!parse_long(s, v)) a.fail(i, expect);
    return v;
  };
  if (single) {
    lo = hi = parse(w, 0);
    if (w.empty()) a.fail(i, expect);
  } else {
    lo = parse(w.substr(0, star), 1);
    hi = parse(w.substr(star + 1), nmax);
  }
  if (lo < 1 || hi > nmax || lo > hi) a.fail(i, expect + " within 1.." + std::to_string(nmax));
}

// A number, or v_name: one value per atom (atom-style) or one for all (equal-style).
struct Value {
  double v = 0;
  std::vector<double> per;
  double at(std::size_t i) const { return per.empty() ? v : per[i]; }
};

Value value(Simulation& sim, const Args& a, std::size_t i, const std::string& what) {
  const std::string& w = a.word(i, what);
  Value val;
  if (w.rfind("v_", 0) != 0) {
    val.v = a.num(i, what);
    return val;
  }
  const std::string name = w.substr(2);
  if (!sim.variables->exists(name)) a.fail(i, "an existing variable after v_ (no variable '" + name + "')");
  try {
    sim.variables->atom_values(name, val.per);
  } catch (const ExpressionError& e) {
    a.fail(i, std::string("a variable that evaluates (") + e.what() + ")");
  }
  return val;
}

void cmd_set(Simulation& sim, const Args& a) {
  if (!sim.domain.box_exists) a.fail(0, "a box first (create_box before set)");
  Atoms& at = sim.atoms;
  if (sim.comm.total(static_cast<long>(at.n)) == 0)  // several ranks: on any rank
    a.fail_line("set command with no atoms existing (create or insert atoms first)");
  const std::string& style = a.word(1, "atom, type, group or region");
  std::vector<char> sel(at.n, 0);
  if (style == "atom") {
    long lo, hi;
    bool single;
    star_bounds(a, 2, std::numeric_limits<int>::max(), lo, hi, single, "an atom ID or ID range");
    const std::size_t one = single ? at.index_of(lo) : Atoms::npos;
    if (single && sim.comm.total(static_cast<long>(one < at.n)) == 0)  // owned here or on another rank
      a.fail(2, "an existing atom ID (there is no atom " + a[2] + ")");
    for (std::size_t i = 0; i < at.n; ++i) sel[i] = at.id[i] >= lo && at.id[i] <= hi;
  } else if (style == "type") {
    long lo, hi;
    bool single;
    star_bounds(a, 2, at.ntypes, lo, hi, single, "an atom type or type range");
    for (std::size_t i = 0; i < at.n; ++i) sel[i] = at.type[i] >= lo && at.type[i] <= hi;
  } else if (style == "group") {
    const int g = sim.groups.existing(a, 2);
    for (std::size_t i = 0; i < at.n; ++i) sel[i] = (at.mask[i] & sim.groups.bit(g)) != 0;
  } else if (style == "region") {
    const Region* r = sim.find_region(a.word(2, "a region ID"));
    if (!r) a.fail(2, "an existing region ID (define it with 'region' first)");
    for (std::size_t i = 0; i < at.n; ++i) sel[i] = r->match(&at.x[3 * i]);
  } else if (style == "mol") {
    a.fail(1, "atom, type, group or region (atom_style granular has no molecule IDs)");
  } else {
    a.fail(1, "atom, type, group or region");
  }
  if (a.size() < 4) a.fail(3, "a keyword and its value");
  sim.print("Setting atom values ...");

  for (std::size_t k = 3; k < a.size();) {
    const std::string& key = a[k];
    long count = 0;
    auto each = [&](auto&& f) {
      for (std::size_t i = 0; i < at.n; ++i)
        if (sel[i]) {
          f(i);
          ++count;
        }
    };
    static const char* xyz[] = {"x", "y", "z", "vx", "vy", "vz", "omegax", "omegay", "omegaz"};
    int comp = -1;
    for (int c = 0; c < 9; ++c)
      if (key == xyz[c]) comp = c;
    if (comp >= 0) {
      const Value v = value(sim, a, k + 1, "a value for " + key);
      std::vector<double>& arr = comp < 3 ? at.x : comp < 6 ? at.v : at.omega;
      each([&](std::size_t i) { arr[3 * i + comp % 3] = v.at(i); });
      k += 2;
    } else if (key == "type") {
      const Value v = value(sim, a, k + 1, "an atom type");
      each([&](std::size_t i) {
        const double t = v.at(i);
        if (t < 1 || t > at.ntypes || t != std::floor(t))
          a.fail(k + 1, "an atom type between 1 and " + std::to_string(at.ntypes) + " (atom " +
                            std::to_string(at.id[i]) + " would get " + std::to_string(t) + ")");
        at.type[i] = static_cast<int>(t);
      });
      k += 2;
    } else if (key == "type/fraction") {
      const long t = a.integer(k + 1, "the new atom type");
      if (t < 1 || t > at.ntypes) a.fail(k + 1, "an atom type between 1 and " + std::to_string(at.ntypes));
      const double frac = a.num(k + 2, "the fraction of atoms to change");
      if (frac < 0 || frac > 1) a.fail(k + 2, "a fraction between 0 and 1");
      const long seed = a.integer(k + 3, "a random seed > 0");
      if (seed <= 0) a.fail(k + 3, "a random seed > 0");
      // Per-atom draw from (seed, id): the same atoms change whatever their storage order.
      for (std::size_t i = 0; i < at.n; ++i)
        if (sel[i] && hashed_uniform(seed, at.id[i]) <= frac) {
          at.type[i] = static_cast<int>(t);
          ++count;
        }
      k += 4;
    } else if (key == "diameter" || key == "density") {
      const Value v = value(sim, a, k + 1, "a " + key);
      const bool diam = key == "diameter";
      each([&](std::size_t i) {
        const double x = v.at(i);
        if (!(x > 0) || !std::isfinite(x)) a.fail(k + 1, diam ? "a finite diameter > 0" : "a finite density > 0");
        const double r = diam ? 0.5 * x : at.radius[i], rho = diam ? at.density[i] : x;
        if (diam)
          at.radius[i] = r;
        else
          at.density[i] = rho;
        if (r > 0 && rho > 0)
          at.rmass[i] = grain_mass(sim, r, rho);
        else if (!diam)
          at.rmass[i] = rho;  // LIGGGHTS: a point particle's density is its mass
      });
      k += 2;
    } else if (key == "mass") {
      const Value v = value(sim, a, k + 1, "a mass");
      each([&](std::size_t i) {
        if (!(v.at(i) > 0)) a.fail(k + 1, "a mass > 0");
        at.rmass[i] = v.at(i);
      });
      k += 2;
    } else if (key == "image") {
      bool given[3];
      long img[3];
      for (int d = 0; d < 3; ++d) {
        given[d] = a.word(k + 1 + d, "an image count or NULL") != "NULL";
        if (!given[d]) continue;
        img[d] = a.integer(k + 1 + d, "an image count or NULL");
        if (img[d] != 0 && !sim.domain.periodic[d])
          a.fail(k + 1 + d, "0 or NULL (axis " + std::string(1, char('x' + d)) + " is not periodic)");
      }
      each([&](std::size_t i) {
        for (int d = 0; d < 3; ++d)
          if (given[d]) at.image[3 * i + d] = static_cast<int>(img[d]);
      });
      k += 4;
    } else if (key == "property/atom") {
      // A fix's per-atom values (fix property/atom ID, fix heat/gran's Temp, heatSource, ...): the column f_NAME.
      const std::string& name = a.word(k + 1, "the name of a per-atom property (Temp, heatSource, ...)");
      const int h = at.find_column("f_" + name);
      if (h < 0)
        a.fail(k + 1, "a per-atom property defined by fix property/atom (its fix ID) or fix heat/gran (Temp, "
                      "heatFlux, heatSource): there is no '" + name + "'");
      const int stride = at.column_stride(h);
      std::vector<Value> vals;
      for (int c = 0; c < stride; ++c) vals.push_back(value(sim, a, k + 2 + c, "a value for " + name));
      std::vector<double>& col = at.column(h);
      each([&](std::size_t i) {
        for (int c = 0; c < stride; ++c) col[i * stride + c] = vals[c].at(i);
      });
      k += 2 + stride;
    } else {
      a.fail(k,
             "a set keyword: type, type/fraction, x, y, z, vx, vy, vz, omegax, omegay, omegaz, diameter, "
             "density, mass, image, property/atom");
    }
    sim.print("  " + std::to_string(sim.comm.total(static_cast<long>(count))) + " settings made for " + key);
  }
}

}  // namespace

SABLE_COMMAND("set", cmd_set);

}  // namespace sable
