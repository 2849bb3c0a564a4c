#pragma once
// Per-atom quantities named as in LIGGGHTS `dump custom` (id type x vx c_ID[2]
// v_name ...), shared by dump custom, dump custom/vtk and compute reduce so the
// three accept the same words and fail the same way on bad ones.
#include <algorithm>
#include <string>
#include <vector>

#include "core/engine/error.h"
#include "core/engine/simulation.h"
#include "core/io/thermo.h"
#include "core/input/variable.h"

namespace sable {

struct AtomColumn {
  enum Kind { ID, TYPE, MASS, X, XS, XU, XSU, IMAGE, V, F, OMEGA, TORQUE, RADIUS, DIAMETER, DENSITY, MOL, COMPUTE, VARIABLE, FIX };
  Kind kind = ID;
  int comp = 0;       // xyz component, or compute/fix column (1-based; 0 = per-atom vector)
  std::string name;   // the word as written in the deck
  std::string ref;    // compute ID or variable name; FIX: the Atoms column f_ID
  bool integer() const { return kind == ID || kind == TYPE || kind == IMAGE || kind == MOL; }
};

inline const char* atom_column_words() {
  return "id, type, mass, x, y, z, xs, ys, zs, xu, yu, zu, xsu, ysu, zsu, ix, iy, iz, vx, vy, vz, fx, fy, fz, "
         "omegax, omegay, omegaz, tqx, tqy, tqz, radius, diameter, density, mol, c_ID, c_ID[N], f_ID, f_ID[N], v_name";
}

// Parses word i of `a` as a per-atom quantity. Unknown words and references to
// missing or non-per-atom computes/variables fail at that word (deck line).
inline AtomColumn parse_atom_column(Simulation& sim, const Args& a, std::size_t i) {
  const std::string& w = a.word(i, std::string("a per-atom attribute: ") + atom_column_words());
  AtomColumn c;
  c.name = w;
  struct Simple {
    const char* word;
    AtomColumn::Kind kind;
    int comp;
  };
  static const Simple simple[] = {
      {"id", AtomColumn::ID, 0},         {"type", AtomColumn::TYPE, 0},       {"mass", AtomColumn::MASS, 0},
      {"x", AtomColumn::X, 0},           {"y", AtomColumn::X, 1},             {"z", AtomColumn::X, 2},
      {"xs", AtomColumn::XS, 0},         {"ys", AtomColumn::XS, 1},           {"zs", AtomColumn::XS, 2},
      {"xu", AtomColumn::XU, 0},         {"yu", AtomColumn::XU, 1},           {"zu", AtomColumn::XU, 2},
      {"xsu", AtomColumn::XSU, 0},       {"ysu", AtomColumn::XSU, 1},         {"zsu", AtomColumn::XSU, 2},
      {"ix", AtomColumn::IMAGE, 0},      {"iy", AtomColumn::IMAGE, 1},        {"iz", AtomColumn::IMAGE, 2},
      {"vx", AtomColumn::V, 0},          {"vy", AtomColumn::V, 1},            {"vz", AtomColumn::V, 2},
      {"fx", AtomColumn::F, 0},          {"fy", AtomColumn::F, 1},            {"fz", AtomColumn::F, 2},
      {"omegax", AtomColumn::OMEGA, 0},  {"omegay", AtomColumn::OMEGA, 1},    {"omegaz", AtomColumn::OMEGA, 2},
      {"tqx", AtomColumn::TORQUE, 0},    {"tqy", AtomColumn::TORQUE, 1},      {"tqz", AtomColumn::TORQUE, 2},
      {"radius", AtomColumn::RADIUS, 0}, {"diameter", AtomColumn::DIAMETER, 0}, {"density", AtomColumn::DENSITY, 0},
      {"mol", AtomColumn::MOL, 0},
  };
  for (const Simple& s : simple)
    if (w == s.word) {
      c.kind = s.kind;
      c.comp = s.comp;
      return c;
    }
  char kind;
  int index;
  // LIGGGHTS writes a fix's per-atom scalar as f_ID[0] too (f_Temp[0]).
  const bool zero = w.rfind("f_", 0) == 0 && w.size() > 5 && w.ends_with("[0]");
  if (!parse_reference(zero ? w.substr(0, w.size() - 3) : w, kind, c.ref, index))
    a.fail(i, std::string("a per-atom attribute: ") + atom_column_words());
  c.comp = index;
  if (kind == 'f') {
    // A fix's per-atom values are the Atoms column f_ID (fix property/atom, heat/gran: f_Temp ...).
    const int h = sim.atoms.find_column("f_" + c.ref);
    if (h < 0)
      a.fail(i, "a per-atom attribute (no fix '" + c.ref +
                    "' with per-atom values: fix property/atom and fix heat/gran (Temp, heatFlux, heatSource) give them)");
    const int stride = sim.atoms.column_stride(h);
    if (index == 0 && stride > 1) a.fail(i, "f_" + c.ref + "[N] (it has " + std::to_string(stride) + " components)");
    if (index > stride)
      a.fail(i, "f_" + c.ref + (stride > 1 ? "[1.." + std::to_string(stride) + "]" : " or f_" + c.ref + "[0]"));
    c.kind = AtomColumn::FIX;
    c.ref = "f_" + c.ref;
    return c;
  }
  if (kind == 'v') {
    if (!sim.variables->exists(c.ref)) a.fail(i, "a defined atom-style variable ('" + c.ref + "' is not defined)");
    if (!sim.variables->is_atom_style(c.ref)) a.fail(i, "an atom-style variable ('" + c.ref + "' is not atom-style)");
    if (index) a.fail(i, "v_name without an index");
    c.kind = AtomColumn::VARIABLE;
    return c;
  }
  const Compute* cp = sim.find_compute(c.ref);
  if (!cp) a.fail(i, "an existing compute ID (no compute '" + c.ref + "')");
  if (!cp->peratom_flag) a.fail(i, "a compute with per-atom output (compute " + c.ref + " is " + cp->style + ")");
  if (index == 0 && cp->peratom_cols > 0)
    a.fail(i, "c_" + c.ref + "[N] (compute " + c.ref + " gives " + std::to_string(cp->peratom_cols) + " columns)");
  if (index > 0 && index > cp->peratom_cols)
    a.fail(i, "a column of compute " + c.ref + " in 1.." + std::to_string(cp->peratom_cols) +
                  (cp->peratom_cols ? "" : " (it gives one value per atom: write c_" + c.ref + ")"));
  c.kind = AtomColumn::COMPUTE;
  return c;
}

// Values of column c for atoms sel (indices into sim.atoms), into out. Computes
// and variables are evaluated here, i.e. only when some output asks for them.
inline void gather_atom_column(Simulation& sim, const AtomColumn& c, const std::vector<std::size_t>& sel,
                               std::vector<double>& out) {
  const Atoms& a = sim.atoms;
  const Domain& d = sim.domain;
  const int k = c.comp;
  out.resize(sel.size());
  auto each = [&](auto f) {
    for (std::size_t j = 0; j < sel.size(); ++j) out[j] = f(sel[j]);
  };
  auto unwrapped = [&](std::size_t i) { return a.x[3 * i + k] + a.image[3 * i + k] * d.length(k); };
  switch (c.kind) {
    case AtomColumn::ID: each([&](std::size_t i) { return static_cast<double>(a.id[i]); }); break;
    case AtomColumn::TYPE: each([&](std::size_t i) { return static_cast<double>(a.type[i]); }); break;
    case AtomColumn::MASS: each([&](std::size_t i) { return a.rmass[i]; }); break;
    case AtomColumn::X: each([&](std::size_t i) { return a.x[3 * i + k]; }); break;
    case AtomColumn::XS: each([&](std::size_t i) { return (a.x[3 * i + k] - d.lo[k]) / d.length(k); }); break;
    case AtomColumn::XU: each(unwrapped); break;
    case AtomColumn::XSU: each([&](std::size_t i) { return (unwrapped(i) - d.lo[k]) / d.length(k); }); break;
    case AtomColumn::IMAGE: each([&](std::size_t i) { return static_cast<double>(a.image[3 * i + k]); }); break;
    case AtomColumn::V: each([&](std::size_t i) { return a.v[3 * i + k]; }); break;
    case AtomColumn::F: each([&](std::size_t i) { return a.f[3 * i + k]; }); break;
    case AtomColumn::OMEGA: each([&](std::size_t i) { return a.omega[3 * i + k]; }); break;
    case AtomColumn::TORQUE: each([&](std::size_t i) { return a.torque[3 * i + k]; }); break;
    case AtomColumn::RADIUS: each([&](std::size_t i) { return a.radius[i]; }); break;
    case AtomColumn::DIAMETER: each([&](std::size_t i) { return 2.0 * a.radius[i]; }); break;
    case AtomColumn::DENSITY: each([&](std::size_t i) { return a.density[i]; }); break;
    case AtomColumn::MOL: {  // granular atoms have no molecule ID: a grain's rigid body (1, 2, ...; 0: none), as LIGGGHTS' multisphere
      each([&](std::size_t i) { return sim.body_of(i).second + 1.0; });
      break;
    }
    case AtomColumn::COMPUTE: {
      // Looked up each time: the compute may have been uncomputed and redefined since parsing.
      Compute* cp = sim.find_compute(c.ref);
      if (!cp || !cp->peratom_flag) fail("'" + c.name + "': compute '" + c.ref + "' no longer exists or is not per-atom");
      cp->peratom_now();
      const std::size_t nc = std::max(1, cp->peratom_cols);
      // Cached this step for other atoms (delete_atoms since): compute again.
      if (cp->peratom.size() != a.n * nc) cp->compute_peratom();
      const std::size_t col = std::max(0, k - 1);
      each([&](std::size_t i) { return cp->peratom[i * nc + col]; });
      break;
    }
    case AtomColumn::FIX: {
      const int h = a.find_column(c.ref);
      if (h < 0) fail("'" + c.name + "': per-atom values '" + c.ref + "' no longer exist");
      const int stride = a.column_stride(h);
      const std::vector<double>& col = a.column(h);
      const int off = std::max(0, k - 1);
      each([&](std::size_t i) { return col[i * stride + off]; });
      break;
    }
    case AtomColumn::VARIABLE: {
      std::vector<double> vals;
      if (!sim.variables->atom_values(c.ref, vals)) fail("'" + c.name + "': variable '" + c.ref + "' no longer exists");
      each([&](std::size_t i) { return vals[i]; });
      break;
    }
  }
}

// `dump_modify region ID|none` and `thresh attr op value|none`: which of the
// dump's atoms are written (shared by dump custom and custom/vtk).
struct DumpFilter {
  std::string region;  // empty: no region filter
  struct Thresh {
    AtomColumn col;
    std::string op;
    double value;
  };
  std::vector<Thresh> thresh;

  // Consumes a region/thresh keyword at a[i]; false if a[i] is neither.
  bool parse(Simulation& sim, const Args& a, std::size_t& i) {
    if (a[i] == "region") {
      const std::string& r = a.word(i + 1, "a region ID or none");
      if (r != "none" && !sim.find_region(r)) a.fail(i + 1, "an existing region ID or none");
      region = r == "none" ? "" : r;
      i += 2;
      return true;
    }
    if (a[i] != "thresh") return false;
    if (a.word(i + 1, "an attribute or none") == "none") {
      thresh.clear();
      i += 2;
      return true;
    }
    Thresh t{parse_atom_column(sim, a, i + 1), a.word(i + 2, "<, <=, >, >=, == or !="), a.num(i + 3, "a threshold")};
    static const char* ops[] = {"<", "<=", ">", ">=", "==", "!="};
    if (std::find_if(std::begin(ops), std::end(ops), [&](const char* o) { return t.op == o; }) == std::end(ops))
      a.fail(i + 2, "<, <=, >, >=, == or !=");
    thresh.push_back(std::move(t));
    i += 4;
    return true;
  }

  void apply(Simulation& sim, std::vector<std::size_t>& sel) const {
    if (!region.empty()) {
      const Region* r = sim.find_region(region);
      if (!r) fail("dump_modify region '" + region + "' no longer exists");
      std::erase_if(sel, [&](std::size_t i) { return !r->match(&sim.atoms.x[3 * i]); });
    }
    std::vector<double> v;
    for (const Thresh& t : thresh) {
      gather_atom_column(sim, t.col, sel, v);
      std::size_t m = 0;
      for (std::size_t j = 0; j < sel.size(); ++j) {
        const double x = v[j], y = t.value;
        const bool keep = t.op == "<" ? x < y : t.op == "<=" ? x <= y : t.op == ">" ? x > y : t.op == ">=" ? x >= y
                        : t.op == "==" ? x == y : x != y;
        if (keep) sel[m++] = sel[j];
      }
      sel.resize(m);
    }
  }
};

}  // namespace sable
