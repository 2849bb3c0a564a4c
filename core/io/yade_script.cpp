// The YADE script sable --export-yade writes (core/io/yade_script.h): Python
// helpers, expressions, and the scene from what the styles added.
#include "core/io/yade_script.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/engine/atoms.h"
#include "core/engine/compute.h"
#include "core/engine/error.h"
#include "core/engine/global_property.h"
#include "core/engine/rigid_bodies.h"
#include "core/engine/simulation.h"
#include "core/input/variable.h"

namespace sable {

std::string yade_num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// Python string literal.
std::string yade_quoted(const std::string& s) {
  std::string o = "'";
  for (char c : s) {
    if (c == '\\' || c == '\'') o += '\\';
    o += c == '\n' ? std::string("\\n") : std::string(1, c);
  }
  return o + "'";
}

// A dump_modify format of one column as Python's % operator takes it: C's
// length modifiers dropped (%ld -> %d); sable checked the conversion at its line.
std::string yade_python_format(const std::string& spec) {
  std::string out;
  for (std::size_t i = 0; i < spec.size(); ++i) {
    out += spec[i];
    if (spec[i] != '%' || i + 1 >= spec.size()) continue;
    if (spec[i + 1] == '%') {
      out += spec[++i];
      continue;
    }
    std::size_t j = i + 1;
    while (j < spec.size() && std::strchr("-+ #0123456789.", spec[j])) out += spec[j++];
    while (j < spec.size() && std::strchr("lhqjzt", spec[j])) ++j;
    i = j - 1;
  }
  return out;
}

// ------------------------------------------------------------------ expressions
// A LAMMPS equal-style formula as a Python expression evaluated in YADE.
std::string YadeScript::translate(const std::string& e, const Args& at, int depth) const {
  if (depth > 20) at.fail_line("export-yade: variables refer to each other in a loop");
  std::string out;
  std::size_t i = 0;
  while (i < e.size()) {
    const char c = e[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      std::size_t k = i;
      while (k < e.size() && (std::isalnum(static_cast<unsigned char>(e[k])) || e[k] == '.' ||
                              ((e[k] == '-' || e[k] == '+') && (e[k - 1] == 'e' || e[k - 1] == 'E'))))
        ++k;
      out += e.substr(i, k - i);
      i = k;
    } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      std::size_t k = i;
      auto word_char = [&](std::size_t j) { return std::isalnum(static_cast<unsigned char>(e[j])) || e[j] == '_'; };
      while (k < e.size() && word_char(k)) ++k;
      // '/' divides, except inside the ID of a fix defined with one (f_ID, ID of a style-like name):
      // the name is extended over '/word' only while the longer ID names a fix.
      while (e.compare(i, 2, "f_") == 0 && k + 1 < e.size() && e[k] == '/' && word_char(k + 1)) {
        std::size_t j = k + 1;
        while (j < e.size() && word_char(j)) ++j;
        if (!sim.find_fix(e.substr(i + 2, j - i - 2))) break;
        k = j;
      }
      const std::string name = e.substr(i, k - i);
      if ((name == "xcm" || name == "count" || name == "mass") && k < e.size() && e[k] == '(') {
        const std::size_t close = e.find(')', k);
        if (close == std::string::npos) at.fail_line("export-yade: no ')' in '" + e + "'");
        out += group_function(name, e.substr(k + 1, close - k - 1), at);
        i = close + 1;
        continue;
      }
      std::string index;
      if (k < e.size() && e[k] == '[') {
        const std::size_t close = e.find(']', k);
        if (close == std::string::npos) at.fail_line("export-yade: no ']' in '" + e + "'");
        index = e.substr(k + 1, close - k - 1);
        k = close + 1;
        if (k < e.size() && e[k] == '[') {  // f_ID[i][j]: index "i][j"
          const std::size_t c2 = e.find(']', k);
          if (c2 == std::string::npos) at.fail_line("export-yade: no ']' in '" + e + "'");
          index += "][" + e.substr(k + 1, c2 - k - 1);
          k = c2 + 1;
        }
      }
      out += term(name, index, at, depth);
      i = k;
    } else if (e.compare(i, 2, "&&") == 0 || e.compare(i, 2, "||") == 0) {
      out += e[i] == '&' ? " and " : " or ";
      i += 2;
    } else if (c == '^') {
      out += "**";
      ++i;
    } else if (std::string("+-*/(),<>=!").find(c) != std::string::npos) {
      out += c;
      ++i;
    } else {
      at.fail_line(std::string("export-yade: cannot translate '") + c + "' in '" + e + "'");
    }
  }
  return out;
}

std::string YadeScript::ids_of(std::uint32_t bits) const {
  std::vector<long> ids;
  for (std::size_t i = 0; i < sim.atoms.n; ++i)
    if (sim.atoms.mask[i] & bits) ids.push_back(sim.atoms.id[i]);
  std::sort(ids.begin(), ids.end());
  std::string o = "[";
  for (long i : ids) o += std::to_string(i) + ", ";
  return o + "]";
}

// Group functions of the group's members now (groups cannot change after the first
// run, export-yade translates the scene once): count and mass as numbers, xcm as the
// members' mass centre in YADE.
std::string YadeScript::group_function(const std::string& name, const std::string& args, const Args& at) const {
  std::vector<std::string> w;
  std::istringstream ss(args);
  for (std::string t; std::getline(ss, t, ',');) {
    t.erase(0, t.find_first_not_of(" \t"));
    t.erase(t.find_last_not_of(" \t") + 1);
    w.push_back(t);
  }
  const int g = w.empty() ? -1 : sim.groups.find(w[0]);
  if (g < 0) at.fail_line("export-yade: " + name + "(" + args + "): no such group");
  const std::uint32_t bit = sim.groups.bit(g);
  if (name == "xcm") {
    if (w.size() != 2 || (w[1] != "x" && w[1] != "y" && w[1] != "z"))
      at.fail_line("export-yade: xcm(" + args + "): expected xcm(group,x|y|z)");
    return "_xcm(" + ids_of(bit) + ", " + std::to_string(w[1][0] - 'x') + ")";
  }
  if (w.size() != 1) at.fail_line("export-yade: " + name + "(" + args + "): expected " + name + "(group)");
  double n = 0, m = 0;
  for (std::size_t i = 0; i < sim.atoms.n; ++i)
    if (sim.atoms.mask[i] & bit) n += 1, m += sim.atoms.rmass[i];
  return yade_num(name == "count" ? n : m);
}

// An equal-style formula of numbers, arithmetic, math functions and variables
// of such formulas only: its value cannot change during a run.
bool YadeScript::constant(const std::string& e, int depth) const {
  static const std::set<std::string> math{"sqrt", "exp", "ln", "log", "abs", "sin", "cos", "tan", "atan2", "atan",
                                          "asin", "acos", "floor", "ceil", "min", "max", "PI", "round"};
  if (depth > 20) return false;
  for (std::size_t i = 0; i < e.size();) {
    const char c = e[i];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      while (i < e.size() && (std::isalnum(static_cast<unsigned char>(e[i])) || e[i] == '.' ||
                              ((e[i] == '-' || e[i] == '+') && (e[i - 1] == 'e' || e[i - 1] == 'E'))))
        ++i;
    } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      std::size_t k = i;
      while (k < e.size() && (std::isalnum(static_cast<unsigned char>(e[k])) || e[k] == '_')) ++k;
      const std::string name = e.substr(i, k - i);
      if (k < e.size() && e[k] == '[') return false;
      if (name.rfind("v_", 0) == 0) {
        const auto it = formulas.find(name.substr(2));
        if (it != formulas.end() ? !constant(it->second, depth + 1) : !sim.variables->exists(name.substr(2)) ||
                                                                          sim.variables->is_atom_style(name.substr(2)))
          return false;
      } else if (!math.count(name)) {
        return false;
      }
      i = k;
    } else if (std::isspace(static_cast<unsigned char>(c)) || std::string("+-*/%^()<>=!&|,?:").find(c) != std::string::npos) {
      ++i;
    } else {
      return false;
    }
  }
  return true;
}

std::string YadeScript::term(const std::string& name, const std::string& index, const Args& at, int depth) const {
  static const std::map<std::string, std::string> per_atom{
      {"vx", "state.vel[0]"},
      {"vy", "state.vel[1]"},   {"vz", "state.vel[2]"},   {"omegax", "state.angVel[0]"},
      {"omegay", "state.angVel[1]"}, {"omegaz", "state.angVel[2]"},
      {"radius", "shape.radius"}};
  static const std::map<std::string, std::string> funcs{
      {"sqrt", "math.sqrt"}, {"exp", "math.exp"}, {"ln", "math.log"}, {"log", "math.log10"}, {"abs", "abs"},
      {"sin", "math.sin"},   {"cos", "math.cos"}, {"tan", "math.tan"}, {"atan2", "math.atan2"},
      {"atan", "math.atan"}, {"asin", "math.asin"}, {"acos", "math.acos"}, {"floor", "math.floor"},
      {"ceil", "math.ceil"}, {"min", "min"},       {"max", "max"},      {"PI", "math.pi"}};
  auto atom = [&] { return "_b(" + std::to_string(std::stol(index)) + ")."; };
  if (!index.empty() && per_atom.count(name)) return atom() + per_atom.at(name);
  if (!index.empty() && (name == "x" || name == "y" || name == "z"))
    return "_pos(" + std::to_string(std::stol(index)) + ", " + std::to_string(name[0] - 'x') + ")";
  if (!index.empty() && name == "mass") return "_m[" + std::to_string(std::stol(index)) + "]";  // the grain's own
  if (!index.empty() && (name == "fx" || name == "fy" || name == "fz"))
    return "O.forces.f(_bid(" + std::to_string(std::stol(index)) + "))[" + std::to_string(name[1] - 'x') + "]";
  if (index.empty() && funcs.count(name)) return funcs.at(name);
  if (name == "step") return "_step[0]";
  if (name == "time") return "(_time0[0] + (_step[0] - _step0[0]) * O.dt)";
  if (name == "dt") return "O.dt";
  if (name == "atoms") return std::to_string(sim.atoms.n);
  if (name == "ke") return "_ke()";
  if (name == "cpu") return "_cpu()";
  if (name.rfind("c_", 0) == 0 && !index.empty() && index.find(']') == std::string::npos)
    if (const Compute* c = sim.find_compute(name.substr(2)))
      if (std::string t = c->export_yade_term(*this, std::stol(index), at); !t.empty()) return t;
  if (name.rfind("v_", 0) == 0 && index.empty() && snaps.count(name.substr(2))) return "_snap[" + yade_quoted(name.substr(2)) + "]";
  if (name.rfind("v_", 0) == 0 && index.empty()) {
    const std::string v = name.substr(2);
    double value = 0;
    if (auto it = formulas.find(v); it != formulas.end()) {
      // numbers only (no state, no step): sable's value, whatever operators it uses (%, round, ...)
      if (constant(it->second, depth) && sim.variables->numeric(v, value)) return yade_num(value);
      return "(" + translate(it->second, at, depth + 1) + ")";
    }
    if (sim.variables->numeric(v, value)) return yade_num(value);
  }
  if (name.rfind("f_", 0) == 0) {
    const auto it = wall_of_fix_.find(name.substr(2));
    const long k = index.empty() ? 0 : std::stol(index);
    if (it != wall_of_fix_.end() && k >= 1 && k <= 3)
      return "O.forces.f(_walls[" + std::to_string(it->second) + "])[" + std::to_string(k - 1) + "]";
    if (set_force_fixes_.count(name.substr(2)) && k >= 1 && k <= 3)  // the group's total force before
      return "_fixf.get(" + yade_quoted(name.substr(2)) + ", Vector3.Zero)[" + std::to_string(k - 1) + "]";
    if (const auto m = std::find(mesh_order_.begin(), mesh_order_.end(), name.substr(2));
        m != mesh_order_.end() && k >= 1 && k <= 9)  // force, torque about the reference point, the point
      return "_mesh_out(" + std::to_string(m - mesh_order_.begin()) + ", " + std::to_string(k) + ")";
    if (is_recorder(name.substr(2)) &&
        k >= 1 && index.find(']') == std::string::npos)  // fix ave/time's last output (value k; row k in vector mode)
      return "_avt[" + yade_quoted(name.substr(2)) + "].value(" + std::to_string(k - 1) + ")";
    if (const auto fz = freeze_bits_.find(name.substr(2)); fz != freeze_bits_.end() && k >= 1 && k <= 3 &&
                                                           index.find(']') == std::string::npos)
      return "_sumf(" + ids_of(fz->second) + ", " + std::to_string(k - 1) + ")";
    if (const auto b = clumps_of_.find(name.substr(2)); b != clumps_of_.end() && index.find("][") != std::string::npos) {
      const long i = std::stol(index), j = std::stol(index.substr(index.find("][") + 2));
      if (i >= 1 && i <= static_cast<long>(b->second.second) && j >= 7 && j <= 9) {  // body i's force: its members'
        std::string ids = "[";
        for (long id : clumps_[b->second.first + i - 1].ids) ids += std::to_string(id) + ", ";
        return "_sumf(" + ids + "], " + std::to_string(j - 7) + ")";
      }
      if (i >= 1 && i <= static_cast<long>(b->second.second) && j >= 1 && j <= 6)  // body i's centre and velocity
        return j <= 3 ? "_wrapped(O.bodies[_cid[" + std::to_string(b->second.first + i - 1) + "]].state.pos[" +
                            std::to_string(j - 1) + "], " + std::to_string(j - 1) + ")"
                      : "O.bodies[_cid[" + std::to_string(b->second.first + i - 1) + "]].state.vel[" + std::to_string(j - 4) + "]";
    }
  }
  at.fail_line("export-yade: cannot translate '" + name + (index.empty() ? "" : "[" + index + "]") +
               "' to YADE (atom values x y z vx vy vz omegax omegay omegaz fx fy fz mass radius [id], "
               "step, time, dt, atoms, ke, v_ of equal-style variables, f_ of a primitive wall's force [1-3], f_ID[1-9] of a mesh, "
               "f_ID[i][1-9] of a rigid body's centre, velocity and force, f_ID[1-3] of aveforce/setforce and freeze, f_ID[k] of ave/time, "
               "xcm(group,dim), count(group), mass(group), c_ID[k] of compute wall/gran/slices)");
}

// ------------------------------------------------------------------ the scene
double YadeScript::type_value(const std::string& prop, int t, const Args& at) const {
  const GlobalProperty* p = GlobalProperty::find(sim, prop);
  if (!p || static_cast<int>(p->values.size()) < t) at.fail_line("export-yade needs fix property/global " + prop + " peratomtype");
  return p->values[t - 1];
}

double YadeScript::pair_value(const std::string& prop, int i, int j, const Args& at) const {
  const GlobalProperty* p = GlobalProperty::find(sim, prop);
  const int n = sim.atoms.ntypes;
  if (!p) at.fail_line("export-yade needs fix property/global " + prop);
  if (p->values.size() == 1) return p->values[0];
  if (static_cast<int>(p->values.size()) < n * n) at.fail_line("export-yade needs " + prop + " peratomtypepair");
  return p->values[(i - 1) * n + (j - 1)];
}

// boundary p on any axis: YADE's cell is periodic on all three, so a fixed axis
// gets a cell 100 box lengths long (nothing meets through it). Positions are
// reported wrapped into sable's box on the periodic axes (YADE keeps them unwrapped).
// (In 2D z never wraps in sable, Domain::wraps, and gets the long cell too: YADE's
// periodic collider takes no body longer than half the cell.)
bool YadeScript::yade_periodic(int k) const { return sim.domain.wraps(k); }

void YadeScript::periodic_cell() {
  const Domain& d = sim.domain;
  if (!d.wraps(0) && !d.wraps(1) && !d.wraps(2)) return;
  py << "O.periodic = True\nO.cell.hSize = Matrix3(";
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      py << (j == k ? yade_num(yade_periodic(k) ? d.length(k) : 100 * d.length(k)) : "0") << (k == 2 && j == 2 ? ")\n" : ", ");
  py << "_wrap = [";
  for (int k = 0; k < 3; ++k)
    py << (yade_periodic(k) ? "(" + yade_num(d.lo[k]) + ", " + yade_num(d.length(k)) + ")" : "None") << (k < 2 ? ", " : "]\n");
}

// One YADE material per atom type; the per-pair values go to MatchMakers.
void YadeScript::materials() {
  const Args& a = sim.pair->args;
  const int n = sim.atoms.ntypes;
  auto beta = [&](int i, int j) {
    const double l = std::log(pair_value("coefficientRestitution", i, j, a));
    return -l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
  };
  py << "_mats = []\n";
  std::ostringstream fric, bn;
  for (int i = 1; i <= n; ++i) {
    const double E = type_value("youngsModulus", i, a), nu = type_value("poissonsRatio", i, a);
    const double mu = pair_value("coefficientFriction", i, i, a);
    if (model == "hertz")
      py << "_mats.append(O.materials.append(FrictMat(young=" << yade_num(E) << ", poisson=" << yade_num(nu)
          << ", frictionAngle=math.atan(" << yade_num(mu) << "), density=1000)))\n";
    else
      py << "_mats.append(O.materials.append(FrictViscoMat(young=" << yade_num(E) << ", poisson=" << yade_num(nu)
          << ", frictionAngle=math.atan(" << yade_num(mu) << "), betan=" << yade_num(beta(i, i)) << ", density=1000)))\n";
    for (int j = i; j <= n; ++j) {
      fric << "(" << i - 1 << ", " << j - 1 << ", math.atan(" << yade_num(pair_value("coefficientFriction", i, j, a)) << ")), ";
      // LIGGGHTS' Hertz dashpot 2 sqrt(5/6) |beta| sqrt(m* S) is YADE's 2 betan sqrt(m* kn) with betan = sqrt(5/6) |beta|.
      bn << "(" << i - 1 << ", " << j - 1 << ", " << yade_num(std::sqrt(5.0 / 6.0) * beta(i, j)) << "), ";
      if (model != "hertz" && std::fabs(beta(i, j) - 0.5 * (beta(i, i) + beta(j, j))) > 1e-12)
        a.fail_line("export-yade: linear/kneib maps onto FrictViscoMat's per-material betan; coefficientRestitution "
                    "between types " + std::to_string(i) + " and " + std::to_string(j) + " is not their mean");
    }
  }
  if (model == "hertz") wall_materials(a);
  auto surface = [&](int material, long type) {
    if (material < 0) return;
    const int t = grain_type_;
    fric << "(" << t - 1 << ", " << material << ", math.atan(" << yade_num(pair_value("coefficientFriction", t, type, a)) << ")), ";
    bn << "(" << t - 1 << ", " << material << ", " << yade_num(std::sqrt(5.0 / 6.0) * beta(t, type)) << "), ";
  };
  for (const Wall& w : walls_) surface(w.material, w.type);
  for (const auto& id : mesh_order_) surface(meshes_.at(id).material, meshes_.at(id).type);
  py << "_fric = MatchMaker(matches=[" << fric.str() << "])\n";
  if (model == "hertz")
    py << "_betan = MatchMaker(matches=[" << bn.str() << "])\n"
        << "_ip2 = Ip2_FrictMat_FrictMat_MindlinPhys(betan=_betan, betas=_betan, frictAngle=_fric)\n"
        << "_law2 = Law2_ScGeom_MindlinPhys_Mindlin()"
        << (limit_force ? "\n" : "  # clips the damped normal force at 0: sable's limitForce on, not set in the deck\n");
  else
    py << "_ip2 = Ip2_FrictViscoMat_FrictViscoMat_FrictViscoPhys(frictAngle=_fric)\n"
        << "_law2 = Law2_ScGeom_FrictViscoPhys_CundallStrackVisco()\n";
}

// YADE's Hertz contact of a sphere with a wall takes R = r/2
// (Ig2_Wall_Sphere_ScGeom gives the wall the grain's radius), with a facet
// R = 2r/3 (Ig2_Facet_Sphere_ScGeom: 2r), LIGGGHTS' R = r for both. A material
// of its own per wall or mesh, (E_b, nu_b), restores LIGGGHTS' kn = 4/3 Y* sqrt(r dn)
// and kt = 8 G* sqrt(r dn) for the grains' type: with s = sqrt(r / R_YADE), YADE's
// E* = E_a E_b / ((1 - nu_a^2) E_b + (1 - nu_b^2) E_a) must be s Y*, and its
// G / (2 - nu) (G, nu: means of the two) 2 s G*.
void YadeScript::wall_materials(const Args& pair) {
  if (walls_.empty() && mesh_order_.empty()) return;
  std::set<int> types(sim.atoms.type.begin(), sim.atoms.type.begin() + sim.atoms.n);
  const Fix& first = walls_.empty() ? *meshes_.at(mesh_order_[0]).fix : *walls_[0].fix;
  if (types.size() != 1)
    first.args.fail_line("export-yade: a Hertz wall or mesh is matched to one grain type (YADE's wall radius "
                         "convention), the deck has " + std::to_string(types.size()));
  grain_type_ = *types.begin();
  int next_id = sim.atoms.ntypes;
  for (Wall& w : walls_) w.material = hertz_surface_material(*w.fix, w.type, std::sqrt(2.0), "wall " + w.fix->id + ": R = r/2", pair, next_id);
  for (const auto& id : mesh_order_) {
    MeshWall& m = meshes_.at(id);
    m.material = hertz_surface_material(*m.fix, m.type, std::sqrt(1.5), "mesh " + id + ": R = 2r/3", pair, next_id);
  }
}

int YadeScript::hertz_surface_material(const Fix& f, long type, double s, const std::string& note, const Args& pair,
                                         int& next_id) {
  const int a = grain_type_;
  const double Ea = type_value("youngsModulus", a, pair), na = type_value("poissonsRatio", a, pair);
  const double Ga = Ea / (2 * (1 + na));
  const double Ew = type_value("youngsModulus", type, pair), nw = type_value("poissonsRatio", type, pair);
  const double Y = 1 / ((1 - na * na) / Ea + (1 - nw * nw) / Ew);
  const double G = 1 / (2 * (2 - na) * (1 + na) / Ea + 2 * (2 - nw) * (1 + nw) / Ew);
  const double q = 1 / (s * Y) - (1 - na * na) / Ea;  // (1 - nu_b^2) / E_b
  auto excess = [&](double nb) { return 0.5 * (Ga + (1 - nb) / (2 * q)) / (2 - 0.5 * (na + nb)) - 2 * s * G; };
  double lo = -0.99, hi = 0.99;
  if (q <= 0 || excess(lo) * excess(hi) > 0)
    f.args.fail_line("export-yade: no YADE material reproduces this Hertz wall's stiffness");
  for (int it = 0; it < 200; ++it) ((excess(lo) > 0) == (excess(0.5 * (lo + hi)) > 0) ? lo : hi) = 0.5 * (lo + hi);
  const double nb = 0.5 * (lo + hi), Eb = (1 - nb * nb) / q;
  const double mu = pair_value("coefficientFriction", a, type, pair);
  py << "O.materials.append(FrictMat(young=" << yade_num(Eb) << ", poisson=" << yade_num(nb) << ", frictionAngle=math.atan("
      << yade_num(mu) << "), density=1000))  # " << note << " in YADE, see export_yade.cpp\n";
  return next_id++;
}

// YADE's periodic collider needs every body shorter than 0.99 of the cell.
void YadeScript::periodic_fit(const MeshWall& w, std::size_t t) const {
  const Domain& d = sim.domain;
  for (int k = 0; k < 3; ++k) {
    if (!yade_periodic(k)) continue;
    double lo = 1e300, hi = -1e300;
    for (int c = 0; c < 3; ++c) {
      const double x = w.mesh->to_world(w.mesh->corner(static_cast<int>(t), c))[k];
      lo = std::min(lo, x), hi = std::max(hi, x);
    }
    if (hi - lo >= 0.99 * d.length(k))
      w.fix->args.fail_line("export-yade: triangle " + std::to_string(t + 1) + " of this mesh spans " +
                            std::string(1, "xyz"[k]) + " across 0.99 of the periodic box or more, which YADE's "
                            "periodic collider does not take (cut the mesh into shorter triangles)");
  }
}

// The facets of each mesh a wall uses, in the world frame, its reference
// point, and one step of its motion (for the torque's lever arms).
void YadeScript::mesh_facets() {
  py << "_meshes = []\n";
  for (const auto& id : mesh_order_) {
    const MeshWall& w = meshes_.at(id);
    const TriMesh& m = *w.mesh;
    py << "_meshes.append(_facets([  # fix " << id << ": " << m.ntri() << " triangles\n";
    for (std::size_t t = 0; t < m.ntri(); ++t) {
      periodic_fit(w, t);
      py << " (";
      for (int k = 0; k < 3; ++k) {
        const Vec3d p = m.to_world(m.corner(static_cast<int>(t), k));
        py << yade_num(p[0]) << ", " << yade_num(p[1]) << ", " << yade_num(p[2]) << ", ";
      }
      py << "),\n";
    }
    const Vec3d r = m.to_world(m.ref_body);
    auto v3 = [](const Vec3d& v) { return "(" + yade_num(v[0]) + ", " + yade_num(v[1]) + ", " + yade_num(v[2]) + ")"; };
    py << "], " << w.material << ", " << v3(r) << ", (" << v3(w.origin) << ", " << v3(w.axis) << ", " << yade_num(w.angle)
        << ", " << v3(w.shift) << ")))\n";
  }
}

// Primitive walls: utils.wall (an infinite plane, both sides) in a box with no
// periodic axis. In a periodic cell, where YADE's collider takes no body longer than
// half the cell, each wall is a fixed utils.box instead: thickness 1e-8 of the
// smallest grain radius, centred on the plane (either side acts, as sable's plane,
// the face 5e-9 r_min off it), spanning twice sable's box on the other axes (YADE's
// cell is 100 box lengths there: no periodic image comes near). YADE's box contact
// (Ig2_Box_Sphere_ScGeom) gives the wall contact's refR = r on both sides, so the
// same material and law (kn = E r for FrictViscoPhys); its contact point is
// at r - dn/2 from the centre, sable's lever arm cri = r - dn/2 (utils.wall's lies on
// the plane). Refused: a wall spanning an axis periodic in the cell (one box cannot
// span the period, boxes side by side would touch a grain twice at their seams) and
// a wall along a periodic axis outside sable's box (its plane would not be where the
// grains meet it).
void YadeScript::walls() {
  const Domain& d = sim.domain;
  py << "_walls = []\n";
  boxes_ = !walls_.empty() && (d.wraps(0) || d.wraps(1) || d.wraps(2));
  double rmin = 1e300;
  for (std::size_t i = 0; i < sim.atoms.n; ++i) rmin = std::min(rmin, sim.atoms.radius[i]);
  for (const Wall& w : walls_) {
    const std::string mat = w.material >= 0 ? std::to_string(w.material) : "_mats[" + std::to_string(w.type - 1) + "]";
    const std::string mask = w.mask != 1 ? ", mask=" + std::to_string(w.mask) : "";
    if (!boxes_) {
      py << "_walls.append(O.bodies.append(utils.wall(" << yade_num(w.pos) << ", axis=" << w.axis << ", sense=0, material="
          << mat << mask << ")))  # fix " << w.fix->id << "\n";
      continue;
    }
    const Args& a = w.fix->args;
    for (int k = 0; k < 3; ++k)
      if (k != w.axis && yade_periodic(k))
        a.fail_line(std::string("export-yade: this ") + "xyz"[w.axis] + "plane spans the periodic " + "xyz"[k] +
                    " axis, which YADE cannot take: its periodic collider needs every body shorter than half the "
                    "cell, and boxes side by side would touch a grain twice at their seams (translated: walls whose "
                    "plane spans non-periodic axes only, z counting as such in 2D)");
    if (d.wraps(w.axis) && (w.pos < d.lo[w.axis] || w.pos >= d.hi[w.axis]))
      a.fail_line(std::string("export-yade: this ") + "xyz"[w.axis] + "plane lies outside the periodic box (" +
                  yade_num(d.lo[w.axis]) + " to " + yade_num(d.hi[w.axis]) + "); put it inside the period");
    const double t = 1e-8 * rmin;
    double c[3], h[3];
    for (int k = 0; k < 3; ++k) {
      c[k] = k == w.axis ? w.pos : 0.5 * (d.lo[k] + d.hi[k]);
      h[k] = k == w.axis ? 0.5 * t : d.length(k);
    }
    py << "_walls.append(O.bodies.append(utils.box((" << yade_num(c[0]) << ", " << yade_num(c[1]) << ", " << yade_num(c[2]) << "), ("
        << yade_num(h[0]) << ", " << yade_num(h[1]) << ", " << yade_num(h[2]) << "), fixed=True, material=" << mat << mask
        << ")))  # fix " << w.fix->id << ": " << "xyz"[w.axis] << "plane " << yade_num(w.pos) << " as a thin box (periodic cell)\n";
  }
}

// The grains, by atom id, with sable's own mass and moment of inertia.
void YadeScript::bodies() {
  const Atoms& at = sim.atoms;
  std::vector<std::size_t> order(at.n);
  for (std::size_t i = 0; i < at.n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](auto p, auto q) { return at.id[p] < at.id[q]; });
  const bool two_d = sim.domain.dimension == 2;
  py << "# id, type, x, y, z, r, m, I, vx, vy, vz, wx, wy, wz, fixed, blockedDOFs\n_grains = [\n";
  for (std::size_t i : order) {
    std::string dofs = fixed_[i] ? "xyzXYZ" : blocked_[i];
    if (!fixed_[i] && two_d) dofs += std::string(dofs.find('z') == std::string::npos ? "z" : "") + "XY";
    if (!fixed_[i] && !rotation_) dofs += "XYZ";
    std::string uniq;
    for (char c : std::string("xyzXYZ"))
      if (dofs.find(c) != std::string::npos && !in_body_[i]) uniq += c;
    py << " (" << at.id[i] << ", " << at.type[i];
    double u[3];  // unwrapped: a rigid body across a periodic boundary stays whole (YADE wraps for contacts)
    sim.domain.unmap(&at.x[3 * i], &at.image[3 * i], u);
    for (int k = 0; k < 3; ++k) py << ", " << yade_num(u[k]);
    py << ", " << yade_num(at.radius[i]) << ", " << yade_num(at.rmass[i]) << ", " << yade_num(at.inertia(i));
    for (int k = 0; k < 3; ++k) py << ", " << yade_num(fixed_[i] ? 0.0 : at.v[3 * i + k]);
    for (int k = 0; k < 3; ++k) py << ", " << yade_num(fixed_[i] || !rotation_ ? 0.0 : at.omega[3 * i + k]);
    py << ", " << (fixed_[i] ? "True" : "False") << ", '" << uniq << "'),\n";
  }
  py << "]\n";
  grain_masks(order);
  py << "_aid, _m, _type = {}, {}, {}\n"
         "for (i, t, x, y, z, r, m, I, vx, vy, vz, wx, wy, wz, fixed, dofs) in _grains:\n"
         "    b = utils.sphere((x, y, z), r, material=_mats[t - 1], fixed=fixed, mask=_mask.get(i, 1))\n"
         "    b.state.mass, b.state.inertia = m, Vector3(I, I, I)\n"
         "    b.state.vel, b.state.angVel = Vector3(vx, vy, vz), Vector3(wx, wy, wz)\n"
         "    b.state.blockedDOFs = dofs\n"
         "    _aid[i] = O.bodies.append(b)\n"
         "    _m[i], _type[i] = m, t\n"
         "_atom_of = {b: i for i, b in _aid.items()}\n";
  for (const auto& m : moves_) py << m << "\n";
  clumps();
}

// A restart's grain-grain contacts keep their tangential spring in sable (read_restart:
// the history is injected at the next run's set-up). YADE's CundallStrack laws keep
// the spring as a force: shearForce = ks * shear (sable's Ft on i = -kt shear, YADE's
// force on id1 = -shearForce, and the shear increment it subtracts is id2's motion
// relative to id1). The interaction is made now, marked not fresh (a fresh one's shear
// force is zeroed on its first step). linear/kneib only: YADE's Mindlin law grows its
// spring incrementally with a stiffness of the overlap, not a stored displacement, so a
// Hertz deck's restart history is refused.
void YadeScript::contact_history() {
  const auto& r = sim.restart;
  if (r.contacts.count() == 0) return;
  const std::size_t ns = r.slots.size();
  int sx = -1;
  for (std::size_t k = 0; k < ns; ++k)
    if (r.slots[k].name == "shearx") sx = static_cast<int>(k);
  if (model != "linear/kneib" || sx < 0 || sx + 2 >= static_cast<int>(ns) || r.slots[sx + 1].name != "sheary" ||
      r.slots[sx + 2].name != "shearz")
    first_run->fail_line("export-yade: the restart " + r.file + " holds " + std::to_string(r.contacts.count()) +
         " contacts with tangential history, which export-yade carries into YADE for model linear/kneib only "
         "(shearx sheary shearz, FrictViscoPhys' shear force); not translated");
  py << "# the restart's " << r.contacts.count() << " contacts: id_i, id_j, sable's shear (x, y, z); YADE's shearForce = ks shear\n"
         "_hist = [\n";
  for (std::size_t c = 0; c < r.contacts.count(); ++c) {
    const HistoryStore::Key key = r.contacts.key(c);
    py << " (" << key.tag << ", " << key.partner;
    for (int k = 0; k < 3; ++k) py << ", " << yade_num(r.contacts.row(c)[sx + k]);
    py << "),\n";
  }
  py << "]\n"
         "_hist_lost = 0\n"
         "for (i, j, sx, sy, sz) in _hist:\n"
         "    try:\n"
         "        I = utils.createInteraction(_aid[i], _aid[j])\n"
         "    except Exception:\n"
         "        _hist_lost += 1\n"
         "        continue\n"
         "    I.iterMadeReal = -1  # not fresh: the law keeps the shear force set here\n"
         "    I.phys.shearForce = I.phys.ks * Vector3(sx, sy, sz)\n"
         "if _hist_lost:\n"
         "    print('export-yade: %d of the restart\\'s %d contacts do not touch in YADE; their tangential springs are lost' % (_hist_lost, len(_hist)), flush=True)\n";
}

// A primitive wall acting on a group (fix ID GROUP wall/gran ...) gets a YADE
// groupMask bit of its own; every grain has bit 1 (grains touch each other and the
// walls of group all) plus the bits of the walls whose group holds it.
int YadeScript::group_mask(const Fix& f) {
  for (const Wall& w : walls_)
    if (w.mask != 1 && w.fix->groupbit == f.groupbit) return w.mask;
  int used = 1;
  for (const Wall& w : walls_) used |= w.mask;
  for (int bit = 1; bit < 30; ++bit)
    if (!(used & (1 << bit))) return 1 << bit;
  f.args.fail(1, "all, or fewer groups with their own walls (export-yade: 29 at most, YADE's groupMask bits)");
}

void YadeScript::grain_masks(const std::vector<std::size_t>& order) {
  const Atoms& at = sim.atoms;
  py << "_mask = {";
  for (std::size_t i : order) {
    int m = 1;
    for (const Wall& w : walls_)
      if (w.mask != 1 && (at.mask[i] & w.fix->groupbit)) m |= w.mask;
    if (m != 1) py << at.id[i] << ": " << m << ", ";
  }
  py << "}  # grains in a group with its own wall (groupMask; 1 otherwise)\n";
}

// Rigid bodies: YADE's clump() computes mass and inertia from the materials'
// density; _clump (head()) sets sable's instead, and the members' contact mass.
void YadeScript::clumps() {
  if (clumps_.empty()) return;
  py << "# clumps: member ids, mass, inertia xx yy zz xy xz yz (world frame), vcm, spin, blockedDOFs, members' contact mass\n"
         "_clumps = [\n";
  for (const yade::Clump& c : clumps_) {
    std::string ids, dofs = c.dofs + (sim.domain.dimension == 2 ? "zXY" : ""), uniq;
    for (long id : c.ids) ids += std::to_string(id) + ", ";
    for (char ch : std::string("xyzXYZ"))
      if (dofs.find(ch) != std::string::npos) uniq += ch;
    py << " ([" << ids << "], " << yade_num(c.mass) << ", (";
    for (double v : c.inertia) py << yade_num(v) << ", ";
    py << "), (" << yade_num(c.vcm[0]) << ", " << yade_num(c.vcm[1]) << ", " << yade_num(c.vcm[2]) << "), (" << yade_num(c.omega[0])
        << ", " << yade_num(c.omega[1]) << ", " << yade_num(c.omega[2]) << "), '" << uniq << "', " << yade_num(c.member_mass) << "),\n";
  }
  py << "]\n_cid = [_clump(*c) for c in _clumps]\n";
}

void YadeScript::engines() {
  py << "O.dt = " << yade_num(sim.dt) << "\n";
  py << "_g = Vector3(" << yade_num(gravity_[0]) << ", " << yade_num(gravity_[1]) << ", " << yade_num(gravity_[2]) << ")\n";
  py << "def _add_forces():\n    pass\n";
  for (const auto& f : forces_) py << "    " << f << "\n";
  const bool facets = !mesh_order_.empty();
  // avoidGranularRatcheting=False: the shear increment of a grain pair is then the relative velocity of
  // the contact points (lever arms r - dn/2) times dt, sable's and LIGGGHTS' vtr dt; YADE's default scales
  // the translational part by (r1 + r2) / (r1 + r2 - dn) and takes the full radii as lever arms.
  py << "O.engines = [\n"
         "    ForceResetter(),\n"
         "    InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()" << (facets ? ", Bo1_Facet_Aabb()" : "")
      << (boxes_ ? ", Bo1_Box_Aabb()" : "") << "]),\n"
         "    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(avoidGranularRatcheting=False), Ig2_Wall_Sphere_ScGeom()" << (facets ? ", Ig2_Facet_Sphere_ScGeom()" : "")
      << (boxes_ ? ", Ig2_Box_Sphere_ScGeom()" : "")
      << "], [_ip2], [_law2]),\n";
  // initRun: a PyRunner first fires at iteration 1, so without it step 1 would go without the deck's forces.
  if (!forces_.empty()) py << "    PyRunner(command='_add_forces()', iterPeriod=1, initRun=True),\n";
  for (std::size_t k = 0; k < mesh_order_.size(); ++k) {
    std::string e = meshes_.at(mesh_order_[k]).motion;
    if (e.empty()) continue;
    e.replace(e.find("IDS"), 3, "_meshes[" + std::to_string(k) + "][0]");
    py << "    " << e << ",  # fix move/mesh on " << mesh_order_[k] << "\n";
  }
  py << "    NewtonIntegrator(damping=0, gravity=Vector3(" << yade_num(gravity_[0]) << ", " << yade_num(gravity_[1]) << ", "
      << yade_num(gravity_[2]) << ")),\n"
      << "    PyRunner(command='_thermo_tick()', iterPeriod=1, initRun=True),\n]\n";  // initRun: step 1's rows and samples too
  contact_history();  // utils.createInteraction takes the laws from O.engines
}

// The recorders styles added (fix ave/time), once every wall, mesh and body is known.
void YadeScript::recorders() {
  for (auto& r : recorders_) r.second(*this);
}

// Helpers the script needs before the scene: body lookup, number format, run with thermo rows.
std::string YadeScript::head() const {
  std::string cols;
  for (const auto& c : thermo_cols) cols += (cols.empty() ? "" : " ") + (c == "step" ? std::string("Step") : c);
  return "# YADE 2023 script written by sable --export-yade (tools/export_yade.cpp); run: yade -j1 -n -x THIS.py\n"
         "import math, time\nfrom yade import utils\n"
         "_t_start, _snap = time.time(), {}\n"
         "def _cpu():  # sable's cpu: wall seconds since the start\n    return time.time() - _t_start\n"
         "_step, _step0, _time0 = [0], [0], [0.0]  # sable's step now; sable's step and time at O.iter 0\n_thermo = {'every': 0, 'cols': []}\n"
         "def _bid(i):\n    return _aid[i]\n"
         "def _b(i):\n    return O.bodies[_aid[i]]\n"
         "def _fmt(v):\n    return '%.15g' % v\n"
         "_wrap = [None, None, None]\n"
         "def _wrapped(p, k):  # wrapped into sable's box on a periodic axis\n"
         "    return p if _wrap[k] is None else _wrap[k][0] + (p - _wrap[k][0]) % _wrap[k][1]\n"
         "def _pos(i, k):\n"
         "    return _wrapped(_b(i).state.pos[k], k)\n"
         "def _ke():  # sable's: every grain's own mass\n"
         "    return sum(0.5 * _m[i] * _b(i).state.vel.squaredNorm() for i in _aid)\n"
         "_fixf = {}\n"
         "_g = None  # NewtonIntegrator's gravity (set with the engines)\n"
         "def _sumf(ids, k):  # total force on grains ids after this step's force pass (sable's f holds fix gravity's weight)\n"
         "    return sum((O.forces.f(_aid[i], sync=True) + _g * _m[i] for i in ids), Vector3.Zero)[k]\n"
         "_rows_cache, _slice_cache, _slice_members = {}, {}, {}\n"
         "def _wall_rows(name, w, axis, pos, ids):  # compute wall/gran/slices' local rows, by grain id, once per step:\n"
         "    c = _rows_cache.get(name)  # (id, contact point on the plane, force on the wall) after the step's force pass\n"
         "    if c is None or c[0] != _step[0]:\n"
         "        members = _slice_members.setdefault(name, set(ids))\n"
         "        wid, rows = _walls[w], []\n"
         "        for I in O.interactions.withBody(wid):\n"
         "            other = I.id2 if I.id1 == wid else I.id1\n"
         "            if not I.isReal or _atom_of.get(other) not in members:\n"
         "                continue\n"
         "            F = I.phys.normalForce + I.phys.shearForce  # the force on id2, minus that on id1\n"
         "            p = [_wrapped(O.bodies[other].state.pos[k], k) for k in range(3)]\n"
         "            p[axis] = pos  # the grain's projection on the plane\n"
         "            rows.append((_atom_of[other], p, -F if I.id1 == wid else F))\n"
         "        rows.sort(key=lambda r: r[0])\n"
         "        c = _rows_cache[name] = (_step[0], rows)\n"
         "    return c[1]\n"
         "def _slice(name, k, w, axis, pos, ids, n, dim, lo, hi, clamp):  # compute wall/gran/slices: c_ID[k + 1], once per step\n"
         "    c = _slice_cache.get(name)\n"
         "    if c is None or c[0] != _step[0]:\n"
         "        lo, hi = lo(), hi()\n"
         "        if not hi > lo:\n"
         "            raise RuntimeError('compute %s: at step %d hi = %g is not above lo = %g' % (name, _step[0], hi, lo))\n"
         "        v = [0.0] * n\n"
         "        for i, p, fw in _wall_rows(name, w, axis, pos, ids):\n"
         "            y = p[dim]\n"
         "            s = (0 if clamp else -1) if y < lo else (n - 1 if clamp else -1) if y > hi else \\\n"
         "                min(max(int(math.floor((y - lo) / (hi - lo) * n)), 0), n - 1)\n"
         "            if s >= 0:\n"
         "                v[s] += fw[axis]\n"
         "        c = _slice_cache[name] = (_step[0], v)\n"
         "    return c[1][k]\n"
         "class _TextDump:  # a text dump's schedule (core/io/dump.h): one write per snapshot, '*' a file per step\n"
         "    def __init__(self, name, path, every, box, head):\n"
         "        self.name, self.path, self.every, self.box, self.head = name, path, every, box, head\n"
         "        self.last, self.file = -1, None\n"
         "    def init(self):\n"
         "        pass\n"
         "    def tick(self):\n"
         "        s = _step[0]\n"
         "        if s % self.every or s == self.last:\n"
         "            return\n"
         "        self.last = s\n"
         "        text = self.snapshot(s)\n"
         "        if '*' in self.path:\n"
         "            with open(self.path.replace('*', str(s)), 'w') as f:\n"
         "                f.write(text)\n"
         "            return\n"
         "        if self.file is None:\n"
         "            self.file = open(self.path, 'w')\n"
         "        self.file.write(text)\n"
         "        self.file.flush()\n"
         "class _DumpLocal(_TextDump):  # dump local of compute wall/gran/slices' rows: core/io/dump_local.cpp's text\n"
         "    def __init__(self, name, path, every, box, head, rows, cols):\n"
         "        _TextDump.__init__(self, name, path, every, box, head)\n"
         "        self.rows, self.cols = rows, cols\n"
         "    def snapshot(self, s):\n"
         "        rows = self.rows()\n"
         "        text = 'ITEM: TIMESTEP\\n%d\\nITEM: NUMBER OF ENTRIES\\n%d\\n' % (s, len(rows)) + self.box + self.head\n"
         "        for n, r in enumerate(rows):\n"
         "            text += ''.join((f % (n + 1) if c is None else f % c(r)) for f, c in self.cols) + '\\n'\n"
         "        return text\n"
         "def _xcm(ids, k):  # xcm(group, dim): mass centre, unwrapped\n"
         "    return sum(_m[i] * _b(i).state.pos[k] for i in ids) / sum(_m[i] for i in ids)\n"
         "def _set_forces(name, ids, F, g, ave):  # fix aveforce (ave) / setforce; g: the weight sable counts in already\n"
         "    fs = [O.forces.f(_aid[i], sync=True) + g * _m[i] for i in ids]\n"
         "    total = sum(fs, Vector3.Zero)\n"
         "    base = total / len(fs) if ave else Vector3.Zero\n"
         "    _fixf[name] = total\n"
         "    for i, f in zip(ids, fs):\n"
         "        O.forces.addF(_aid[i], Vector3(*[0 if F[k] is None else base[k] + (F[k]() if callable(F[k]) else F[k]) - f[k]\n"
         "                                          for k in range(3)]))\n"
         "def _facets(tris, mat, ref, step):  # a mesh's facets, its reference point in the first facet's frame, one motion step\n"
         "    ids = [O.bodies.append(utils.facet((Vector3(*t[0:3]), Vector3(*t[3:6]), Vector3(*t[6:9])), material=mat)) for t in tris]\n"
         "    b = O.bodies[ids[0]]\n"
         "    return (ids, b.state.ori.conjugate() * (Vector3(*ref) - b.state.pos), step)\n"
         "def _unstep(q, step):  # where a point of the mesh was when this step's forces were found\n"
         "    o, axis, angle, shift = (Vector3(*step[0]), Vector3(*step[1]), step[2], Vector3(*step[3]))\n"
         "    return o + Quaternion(axis, -angle) * (q - shift - o)\n"
         "def _mesh_out(k, j):  # f_ID[j] of a mesh: force, torque about the reference point (moving with it), the point\n"
         "    ids, off, step = _meshes[k]\n"
         "    ref = O.bodies[ids[0]].state.pos + O.bodies[ids[0]].state.ori * off\n"
         "    if j >= 7:\n"
         "        return ref[j - 7]\n"
         "    ref = _unstep(ref, step)\n"
         "    F = sum((O.forces.f(i, sync=True) for i in ids), Vector3.Zero)\n"
         "    T = sum((O.forces.t(i, sync=True) + (_unstep(O.bodies[i].state.pos, step) - ref).cross(O.forces.f(i, sync=True))\n"
         "             for i in ids), Vector3.Zero)\n"
         "    return F[j - 1] if j <= 3 else T[j - 4]\n"
         "def _clump(ids, M, I, v, w, dofs, member_mass):\n"
         "    c = O.bodies[O.bodies.clump([_aid[i] for i in ids])]\n"
         "    R = c.state.ori.toRotationMatrix()\n"
         "    Iw = Matrix3(I[0], I[3], I[4], I[3], I[1], I[5], I[4], I[5], I[2])\n"
         "    L = R.transpose() * Iw * R\n"
         "    if max(abs(L[0, 1]), abs(L[0, 2]), abs(L[1, 2])) > 1e-9 * L.trace():\n"
         "        raise RuntimeError('clump of atoms %s: principal axes of sable inertia differ from YADE clump frame' % ids)\n"
         "    c.state.mass, c.state.inertia = M, Vector3(L[0, 0], L[1, 1], L[2, 2])\n"
         "    c.state.vel, c.state.angVel, c.state.blockedDOFs = Vector3(*v), Vector3(*w), dofs\n"
         "    c.state.angMom = Iw * c.state.angVel  # what YADE integrates for an aspherical body\n"
         "    for i in ids:  # contacts see the body's mass as each member's (sable, LIGGGHTS)\n"
         "        b = _b(i)\n"
         "        b.state.mass = member_mass\n"
         "        b.state.vel = c.state.vel + c.state.angVel.cross(b.state.pos - c.state.pos)\n"
         "        b.state.angVel = c.state.angVel\n"
         "    return c.id\n"
         "class _AveTime:  # fix ave/time, ave one, scalar or vector mode: fixes/fix_ave_time.cpp's schedule, averages and files\n"
         "    def __init__(self, path, header, nevery, nrepeat, nfreq, start, cols, off, rows=None, h5=None):\n"
         "        self.nevery, self.nrepeat, self.nfreq, self.start = nevery, nrepeat, nfreq, start\n"
         "        self.cols, self.off, self.irepeat, self.rows = cols, off, 0, rows\n"
         "        self.width = len(cols) * (rows or 1)\n"
         "        self.out = [0.0] * self.width  # the last output (0 before the first); row r, value j at r * len(cols) + j\n"
         "        self.file = open(path, 'w') if path else None\n"
         "        if self.file:\n"
         "            self.file.write(header)\n"
         "            self.file.flush()\n"
         "        self.h5 = None\n"
         "        if h5:  # datasets step (records) and values (records x [rows x] values), attributes columns and fix\n"
         "            import h5py, numpy\n"
         "            self.h5 = h5py.File(h5[0], 'w')\n"
         "            shape = ((rows,) if rows else ()) + (len(cols),)\n"
         "            self.h5.create_dataset('values', (0,) + shape, maxshape=(None,) + shape, dtype='f8', chunks=True)\n"
         "            self.h5.create_dataset('step', (0,), maxshape=(None,), dtype='i8', chunks=True)\n"
         "            self.h5.attrs.create('columns', numpy.array(h5[1], dtype=object), dtype=h5py.string_dtype())\n"
         "            self.h5.attrs.create('fix', numpy.array(h5[2], dtype=object), dtype=h5py.string_dtype())\n"
         "            self.h5.flush()\n"
         "        self.nvalid = self.first_after(_step[0])\n"
         "    def value(self, k):  # f_ID[k + 1]: value k, or row k of the first value in vector mode\n"
         "        return self.out[k * len(self.cols) if self.rows else k]\n"
         "    def first_after(self, step):  # LIGGGHTS' nextvalid()\n"
         "        n = (step // self.nfreq) * self.nfreq + self.nfreq\n"
         "        while n < self.start:\n"
         "            n += self.nfreq\n"
         "        if n - self.nfreq == step and self.nrepeat == 1:\n"
         "            n = step\n"
         "        else:\n"
         "            n -= (self.nrepeat - 1) * self.nevery\n"
         "        return n + self.nfreq if n < step else n\n"
         "    def init(self):  # each run's start\n"
         "        if self.nvalid < _step[0]:\n"
         "            self.irepeat, self.nvalid = 0, self.first_after(_step[0])\n"
         "    def tick(self):  # end of step _step[0] (and each run's set-up)\n"
         "        s = _step[0]\n"
         "        if s != self.nvalid:\n"
         "            return\n"
         "        if self.irepeat == 0:\n"
         "            self.sum = [0.0] * self.width\n"
         "        nv = len(self.cols)\n"
         "        for j, c in enumerate(self.cols):\n"
         "            x = c()\n"
         "            for r, xr in enumerate(x if self.rows else [x]):\n"
         "                self.sum[r * nv + j] = xr if self.off[j] else self.sum[r * nv + j] + xr\n"
         "        self.irepeat += 1\n"
         "        if self.irepeat < self.nrepeat:\n"
         "            self.nvalid += self.nevery\n"
         "            return\n"
         "        self.irepeat, self.nvalid = 0, s + self.nfreq - (self.nrepeat - 1) * self.nevery\n"
         "        out = [x if self.off[k % nv] else x / self.nrepeat for k, x in enumerate(self.sum)]\n"
         "        self.out = out\n"
         "        if self.file:\n"
         "            if self.rows:\n"
         "                self.file.write('%d %d\\n' % (s, self.rows) + ''.join(\n"
         "                    '%d' % (r + 1) + ''.join(' %g' % x for x in out[r * nv:(r + 1) * nv]) + '\\n' for r in range(self.rows)))\n"
         "            else:\n"
         "                self.file.write('%d' % s + ''.join(' %g' % x for x in out) + '\\n')\n"
         "            self.file.flush()\n"
         "        if self.h5:\n"
         "            v, st = self.h5['values'], self.h5['step']\n"
         "            v.resize(v.shape[0] + 1, axis=0)\n"
         "            v[-1] = [out[r * nv:(r + 1) * nv] for r in range(self.rows)] if self.rows else out\n"
         "            st.resize(st.shape[0] + 1, axis=0)\n"
         "            st[-1] = s  # last: the record is complete\n"
         "            self.h5.flush()\n"
         "class _DumpCustom(_TextDump):  # dump custom: core/io/dump_custom.cpp's text\n"
         "    def __init__(self, name, path, every, ids, box, head, cols):\n"
         "        _TextDump.__init__(self, name, path, every, box, head)\n"
         "        self.ids, self.cols = ids, cols\n"
         "    def snapshot(self, s):\n"
         "        text = 'ITEM: TIMESTEP\\n%d\\nITEM: NUMBER OF ATOMS\\n%d\\n' % (s, len(self.ids)) + self.box + self.head\n"
         "        for i in self.ids:\n"
         "            text += ''.join(f % (int(c(i)) if f.endswith('d ') else c(i)) for f, c in self.cols) + '\\n'\n"
         "        return text\n"
         "_recorders, _avt = [], {}\n"
         "def _row():\n    print(' '.join('%.10g' % c() for c in _thermo['cols']), flush=True)\n"
         "def _thermo_tick():\n"
         "    _step[0] = _step0[0] + O.iter + 1  # this engine runs after NewtonIntegrator, before O.iter counts the step\n"
         "    for r in _recorders:\n"
         "        r.tick()\n"
         "    if _thermo['every'] and (_step[0] % _thermo['every'] == 0 or _step[0] == _thermo['last']):\n"
         "        _row()\n"
         "def _run(n, every, deck):\n"
         "    _thermo.update(every=every, cols=_thermo_cols, last=_step0[0] + O.iter + n)\n"
         "    for r in _recorders:  # sable: init() and setup() of fix ave/time\n"
         "        r.init()\n"
         "        r.tick()\n"
         "    print(" + yade_quoted(cols) + ", flush=True)\n"
         "    _row()\n"
         "    O.run(n, True)\n"
         "    _step[0] = _step0[0] + O.iter\n"
         "    print('Loop time of run %d steps (YADE)' % n, flush=True)\n";
}

// As core/io/dump_custom.cpp and dump_local.cpp write it.
std::string YadeScript::dump_box() const {
  const Domain& dom = sim.domain;
  char box[256];
  std::snprintf(box, sizeof box, "ITEM: BOX BOUNDS %s %s %s\n%g %g\n%g %g\n%g %g\n", dom.periodic[0] ? "pp" : "ff",
                dom.periodic[1] ? "pp" : "ff", dom.periodic[2] ? "pp" : "ff", dom.lo[0], dom.hi[0], dom.lo[1], dom.hi[1],
                dom.lo[2], dom.hi[2]);
  return box;
}

// ------------------------------------------------------------------ what styles add
void YadeScript::begin_fixes() {
  const std::size_t n = sim.atoms.n;
  fixed_.assign(n, 0);
  blocked_.assign(n, "");
  in_body_.assign(n, 0);
  integrated_.assign(n, 0);
}

void YadeScript::integrate(std::uint32_t groupbit) {
  for (std::size_t i = 0; i < sim.atoms.n; ++i)
    if (sim.atoms.mask[i] & groupbit) integrated_[i] = 1;
}

void YadeScript::freeze(const Fix& f) {
  for (std::size_t i = 0; i < sim.atoms.n; ++i)
    if (sim.atoms.mask[i] & f.groupbit) fixed_[i] = 1;
  freeze_bits_[f.id] = f.groupbit;
}

void YadeScript::add_gravity(const double g[3]) {
  for (int k = 0; k < 3; ++k) gravity_[k] += g[k];
}

void YadeScript::set_forces(const Fix& f, const std::string& python) {
  forces_.push_back(python);
  set_force_fixes_.insert(f.id);
}

// A number, NULL ("None") or v_name (an equal-style variable, as a Python
// expression evaluated each step).
std::string YadeScript::force_component(const Args& a, std::size_t i) const {
  const std::string& w = a.word(i, "a force component (number, v_name or NULL)");
  if (w == "NULL") return "None";
  if (w.rfind("v_", 0) == 0) return "(" + translate(w, a) + ")";
  return yade_num(a.num(i, "a number, v_name or NULL (export-yade)"));
}

void YadeScript::add_wall(const Fix& f, long type, int axis, double pos) {
  wall_of_fix_[f.id] = static_cast<int>(walls_.size());
  walls_.push_back({&f, type, axis, pos});
  if (f.groupbit != 1u) walls_.back().mask = group_mask(f);
}

void YadeScript::add_mesh(const Fix& f, const TriMesh& m, long type) { meshes_[f.id] = {&f, &m, type, -1, ""}; }

int YadeScript::wall_index(const std::string& fix_id) const {
  const auto w = wall_of_fix_.find(fix_id);
  return w == wall_of_fix_.end() ? -1 : w->second;
}

YadeScript::MeshWall* YadeScript::mesh(const std::string& id) {
  const auto it = meshes_.find(id);
  return it == meshes_.end() ? nullptr : &it->second;
}

bool YadeScript::wall_uses_mesh(const std::string& id) const {
  return std::find(mesh_order_.begin(), mesh_order_.end(), id) != mesh_order_.end();
}

void YadeScript::add_clumps(const Fix& f, const std::vector<yade::Clump>& bodies) {
  clumps_of_[f.id] = {clumps_.size(), bodies.size()};
  clumps_.insert(clumps_.end(), bodies.begin(), bodies.end());
  const RigidBodies& rb = *f.rigid_bodies();
  for (std::size_t i = 0; i < sim.atoms.n; ++i)
    if (rb.body_of(i) >= 0) in_body_[i] = 1;
}

void YadeScript::add_recorder(const Fix& f, std::function<void(YadeScript&)> write) {
  recorders_.emplace_back(&f, std::move(write));
}

bool YadeScript::is_recorder(const std::string& fix_id) const {
  return std::any_of(recorders_.begin(), recorders_.end(), [&](const auto& r) { return r.first->id == fix_id; });
}

// Every grain moves in YADE as sable moves it: integrated, frozen or in a body, never two of these.
void YadeScript::check_integrated() const {
  const Atoms& at = sim.atoms;
  for (std::size_t i = 0; i < at.n; ++i)
    if (integrated_[i] && in_body_[i])
      fail("export-yade: atom " + std::to_string(at.id[i]) + " is in a rigid body and integrated on its own too "
           "(fix nve/sphere or move): give that fix a group without the body's grains");
  for (std::size_t i = 0; i < at.n; ++i)
    if (!integrated_[i] && !fixed_[i] && !in_body_[i])
      fail("export-yade: atom " + std::to_string(at.id[i]) + " is neither integrated (fix nve/sphere, move) nor frozen");
}

}  // namespace sable
