#include "core/input/variable.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <set>
#include <vector>

#include "core/engine/error.h"
#include "core/input/expression.h"
#include "core/geometry/region.h"
#include "core/engine/simulation.h"
#include "core/io/thermo.h"

namespace sable {

// What an expression can see of the simulation.
class SimContext : public ExprContext {
 public:
  SimContext(Simulation& sim, const Args& where) : sim(sim), where(where) {}
  Simulation& sim;
  const Args& where;
  std::size_t atom = Atoms::npos;  // atom index for atom-style formulas
  // Atom-style variables met in an atom-style formula, evaluated for all atoms
  // once per evaluation of the formula (not once per atom: nesting was O(N^2)).
  std::map<std::string, std::vector<double>> atom_vars;

  bool thermo_keyword(const std::string& name, double& out) override { return sim.thermo->keyword(name, out); }
  bool variable(const std::string& name, double& out) override {
    if (atom != Atoms::npos && sim.variables->is_atom_style(name)) {
      auto it = atom_vars.find(name);
      if (it == atom_vars.end()) {
        it = atom_vars.emplace(name, std::vector<double>()).first;
        sim.variables->atom_values(name, it->second);
      }
      out = it->second[atom];
      return true;
    }
    return sim.variables->numeric(name, out);
  }
  bool compute_or_fix(char kind, const std::string& id, int index, int column, double& out) override {
    if (kind == 'c') {
      if (column) return false;  // sable computes have no global arrays
      Compute* c = sim.find_compute(id);
      if (!c) return false;
      if (atom != Atoms::npos && c->peratom_flag) {
        c->peratom_now();
        const int nc = std::max(1, c->peratom_cols);
        if (c->peratom.size() != sim.atoms.n * nc) c->compute_peratom();  // cached for other atoms (delete_atoms)
        out = c->peratom[atom * nc + std::max(0, index - 1)];
        return true;
      }
    }
    if (kind == 'f' && atom != Atoms::npos && !column) {  // a fix's per-atom values: the Atoms column f_ID (fix heat/gran's Temp ...)
      const int h = sim.atoms.find_column("f_" + id);
      if (h >= 0 && index <= sim.atoms.column_stride(h)) {
        out = sim.atoms.column(h)[atom * sim.atoms.column_stride(h) + std::max(0, index - 1)];
        return true;
      }
    }
    // No such global value: the caller names the reference in its error.
    GlobalOutput* g = find_global_output(sim, kind, id);
    if (!g || !g->has_global(index, column)) return false;
    out = g->global(index, column);
    return true;
  }
  static bool atom_field_name(const std::string& name) {
    static const std::set<std::string> kNames = {
        "x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz", "omegax", "omegay", "omegaz",
        "tqx", "tqy", "tqz", "radius", "mass", "density", "type", "id"};
    return kNames.count(name) > 0;
  }
  static bool atom_field(const Atoms& a, const std::string& name, std::size_t i, double& out) {
    if (name.size() == 1 && name[0] >= 'x' && name[0] <= 'z') {
      out = a.x[3 * i + (name[0] - 'x')];
      return true;
    }
    static const char* vec3[] = {"v", "f", "omega", "tq"};
    const std::vector<double>* arrays[] = {&a.v, &a.f, &a.omega, &a.torque};
    for (int q = 0; q < 4; ++q) {
      const std::string base = vec3[q];
      if (name.size() == base.size() + 1 && name.compare(0, base.size(), base) == 0) {
        const char c = name.back();
        if (c < 'x' || c > 'z') continue;
        out = (*arrays[q])[3 * i + (c - 'x')];
        return true;
      }
    }
    if (name == "radius") out = a.radius[i];
    else if (name == "mass") out = a.rmass[i];
    else if (name == "density") out = a.density[i];
    else if (name == "type") out = a.type[i];
    else if (name == "id") out = static_cast<double>(a.id[i]);
    else return false;
    return true;
  }
  bool atom_value_by_id(const std::string& name, long id, double& out) override {
    std::size_t i = sim.atoms.index_of(id);
    if (i != Atoms::npos && i >= sim.atoms.n) i = Atoms::npos;  // a ghost: its owner answers
    const bool known = atom_field_name(name);  // the same answer on every rank
    out = 0.0;
    if (i != Atoms::npos && known) atom_field(sim.atoms, name, i, out);
    if (sim.comm.distributed) {  // the rank that owns the grain gives its value to all
      double got[2] = {i != Atoms::npos ? out : 0.0, i != Atoms::npos ? 1.0 : 0.0};
      sim.comm.total(got, 2);
      out = got[0];
      i = got[1] > 0 ? 0 : Atoms::npos;
    }
    if (i == Atoms::npos) where.fail_line("atom ID " + std::to_string(id) + " in '" + name + "[" +
                                          std::to_string(id) + "]' does not exist");
    return known;
  }
  bool atom_value_local(const std::string& name, std::size_t i, double& out) override {
    return atom_field(sim.atoms, name, i, out);
  }
  bool group_function(const std::string& func, const std::vector<std::string>& args, double& out) override;
};

bool SimContext::group_function(const std::string& func, const std::vector<std::string>& args, double& out) {
  if (args.empty()) return false;
  const int g = sim.groups.find(args[0]);
  if (g < 0) where.fail_line("group '" + args[0] + "' in " + func + "() does not exist");
  const std::uint32_t bit = sim.groups.bit(g);
  const Atoms& a = sim.atoms;
  auto axis = [&](std::size_t k) {
    if (args.size() <= k || args[k].size() != 1 || args[k][0] < 'x' || args[k][0] > 'z')
      where.fail_line(func + "(" + args[0] + ", ...) needs x, y or z as argument " + std::to_string(k + 1));
    return args[k][0] - 'x';
  };
  // LAMMPS' optional last argument: a region that further restricts the group.
  const std::size_t nfix = func == "count" || func == "mass" ? 1 : 2;
  const Region* reg = nullptr;
  if (args.size() > nfix + 1)
    where.fail_line(func + "(" + args[0] + ", ...): too many arguments (expected at most " + std::to_string(nfix + 1) + ")");
  if (args.size() == nfix + 1 && !(reg = sim.find_region(args[nfix])))
    where.fail_line("region '" + args[nfix] + "' in " + func + "() does not exist");
  auto in = [&](std::size_t i) { return (a.mask[i] & bit) && (!reg || reg->match(&a.x[3 * i])); };
  double count = 0, mass = 0, s[3] = {0, 0, 0};
  if (func == "count" || func == "mass") {
    for (std::size_t i = 0; i < a.n; ++i)
      if (in(i)) {
        count += 1;
        mass += a.rmass[i];
      }
    out = sim.comm.total(func == "count" ? count : mass);
    return true;
  }
  if (func == "xcm" || func == "vcm" || func == "fcm") {
    const int k = axis(1);
    for (std::size_t i = 0; i < a.n; ++i) {
      if (!in(i)) continue;
      if (func == "fcm") {
        s[k] += a.f[3 * i + k];
        continue;
      }
      double val = func == "vcm" ? a.v[3 * i + k] : 0.0;
      if (func == "xcm") {
        double u[3];
        sim.domain.unmap(&a.x[3 * i], &a.image[3 * i], u);
        val = u[k];
      }
      s[k] += a.rmass[i] * val;
      mass += a.rmass[i];
    }
    s[k] = sim.comm.total(s[k]);
    mass = sim.comm.total(mass);
    out = func == "fcm" ? s[k] : (mass > 0 ? s[k] / mass : 0.0);
    return true;
  }
  if (func == "bound") {
    if (args.size() < 2) where.fail_line("bound(group, xmin|xmax|ymin|...) needs two arguments");
    const std::string& w = args[1];
    if (w.size() != 4 || w[0] < 'x' || w[0] > 'z' || (w.substr(1) != "min" && w.substr(1) != "max"))
      where.fail_line("bound() second argument '" + w + "': expected xmin, xmax, ymin, ymax, zmin or zmax");
    const int k = w[0] - 'x';
    const bool mx = w.substr(1) == "max";
    // An empty group gives LIGGGHTS' (LAMMPS') sentinels: min 1e20, max -1e20.
    constexpr double kBig = 1.0e20;
    double b = mx ? -kBig : kBig;
    for (std::size_t i = 0; i < a.n; ++i)
      if (in(i)) b = mx ? std::max(b, a.x[3 * i + k]) : std::min(b, a.x[3 * i + k]);
    out = mx ? sim.comm.highest(b) : sim.comm.lowest(b);
    return true;
  }
  return false;
}

Variables::Variables(Simulation& sim) : sim_(sim) {}
Variables::~Variables() = default;

void Variables::define_index(const std::string& name, const std::vector<std::string>& values) {
  Var v;
  v.style = "index";
  v.values = values;
  v.where.file = "command line -var";
  vars_[name] = std::move(v);
}

void Variables::define(const Args& a) {
  const std::string& name = a.word(1, "a variable name");
  const std::string& style = a.word(2, "a variable style (index, loop, string, equal, atom, delete)");
  if (style == "delete") {
    vars_.erase(name);
    return;
  }
  Var v;
  v.style = style;
  if (style == "index") {
    if (vars_.count(name)) return;  // LAMMPS: an index variable (e.g. from -var) is not redefined
    a.need(4, "at least one value for the index variable");
    for (std::size_t i = 3; i < a.size(); ++i) v.values.push_back(a[i]);
  } else if (style == "loop") {
    if (vars_.count(name)) return;
    // LAMMPS: loop N (1..N, N >= 1) or loop N1 N2 (N1 <= N2, N2 >= 0); values are made
    // one at a time, so a loop of 1e9 values costs nothing until it is stepped through.
    long lo = 1, hi = a.integer(3, "the loop count N (or N1 N2)");
    std::size_t k = 4;
    if (a.size() > 4 && a[4] != "pad") {
      lo = hi;
      hi = a.integer(4, "the loop end N2");
      if (hi < lo) a.fail(4, "a loop end N2 >= N1 = " + std::to_string(lo) + " (the loop would be empty)");
      k = 5;
    } else if (hi < 1) {
      a.fail(3, "a loop count N >= 1 (the loop would be empty)");
    }
    if (hi < 0) a.fail(k - 1, "a loop end >= 0");
    if (static_cast<double>(hi) - static_cast<double>(lo) >= 1e15) a.fail(k - 1, "a loop of fewer than 1e15 values");
    if (a.size() > k) {
      if (a[k] != "pad") a.fail(k, "'pad' or nothing");
      if (lo < 0) a.fail(k, "no 'pad' with a negative loop start (" + std::to_string(lo) + ")");
      v.pad = static_cast<int>(std::to_string(hi).size());
    }
    if (a.size() > k + 1) a.fail(k + 1, "nothing after 'pad'");
    v.first = lo;
    v.count = hi - lo + 1;
  } else if (style == "string") {
    a.need(4, "the string value");
    v.values.push_back(a.joined(3));
  } else if (style == "equal" || style == "atom") {
    a.need(4, "a formula");
    v.values.push_back(a.joined(3));
    try {
      v.expr = std::make_shared<Expression>(v.values[0]);
    } catch (const ExpressionError& e) {
      a.fail(3, std::string("a valid formula: ") + e.what());
    }
    check_names(a, *v.expr, style == "atom");
  } else {
    a.fail(2, "a variable style: index, loop, string, equal, atom or delete");
  }
  v.where = a.where();
  vars_[name] = std::move(v);
}

bool Variables::next(const std::string& name, const Args& where) {
  auto it = vars_.find(name);
  if (it == vars_.end()) where.fail(1, "a defined variable for 'next' ('" + name + "' is not defined)");
  Var& v = it->second;
  if (v.style != "index" && v.style != "loop") where.fail(1, "an index or loop variable for 'next'");
  if (++v.which >= size(v)) {
    vars_.erase(it);
    return false;
  }
  return true;
}

double Variables::evaluate(const std::string& expr, const Args& where) {
  SimContext ctx(sim_, where);
  try {
    return Expression(expr).eval(ctx);
  } catch (const ExpressionError& e) {
    where.fail_line(std::string("in formula '") + expr + "': " + e.what());
  }
}

std::string Variables::string_value(const std::string& name, const Args& where) {
  auto it = vars_.find(name);
  if (it == vars_.end()) where.fail_line("variable '" + name + "' is not defined (use 'variable " + name + " ...' first)");
  Var& v = it->second;
  if (v.style == "atom") where.fail_line("atom-style variable '" + name + "' cannot be used as ${" + name + "}");
  if (v.style != "equal") return current(v);
  if (++depth_ > 50) {
    depth_ = 0;
    where.fail_line("variable '" + name + "' refers to itself");
  }
  SimContext ctx(sim_, where);
  double val;
  try {
    val = v.expr->eval(ctx);
  } catch (const ExpressionError& e) {
    --depth_;
    where.fail_line("in variable '" + name + "' = '" + v.values[0] + "': " + e.what());
  }
  --depth_;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.15g", val);
  return buf;
}

bool Variables::numeric(const std::string& name, double& out) {
  auto it = vars_.find(name);
  if (it == vars_.end()) return false;
  Var& v = it->second;
  if (v.style == "atom") return false;
  if (v.style == "equal") {
    struct Guard {
      int& d;
      ~Guard() { --d; }
    } g{++depth_};
    if (depth_ > 50) throw ExpressionError("variable '" + name + "' refers to itself");
    const Args here({"variable", name}, v.where);  // errors of what it reads name its definition
    SimContext ctx(sim_, here);
    if (depth_ > 1) {
      out = v.expr->eval(ctx);
      return true;
    }
    try {  // the outermost variable names where it was defined (it is evaluated at output time)
      out = v.expr->eval(ctx);
    } catch (const ExpressionError& e) {
      throw ExpressionError(std::string(e.what()) + " (variable '" + name + "' defined at " + v.where.file + ":" +
                            std::to_string(v.where.line) + ")");
    }
    return true;
  }
  const std::string s = current(v);
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  if (!end || *end) throw ExpressionError("variable '" + name + "' = '" + s + "' is not a number");
  return true;
}

bool Variables::is_atom_style(const std::string& name) const {
  auto it = vars_.find(name);
  return it != vars_.end() && it->second.style == "atom";
}

bool Variables::atom_values(const std::string& name, std::vector<double>& out) {
  auto it = vars_.find(name);
  if (it == vars_.end()) return false;
  Var& v = it->second;
  out.assign(sim_.atoms.n, 0.0);
  const Args here({"variable", name}, v.where);
  SimContext ctx(sim_, here);
  if (v.style != "atom") {
    double val;
    numeric(name, val);
    std::fill(out.begin(), out.end(), val);
    return true;
  }
  // Atom-style variables that refer to each other would recurse without end.
  struct Guard {
    int& d;
    ~Guard() { --d; }
  } g{++depth_};
  if (depth_ > 50)
    throw ExpressionError("atom-style variable '" + name + "' refers to itself (directly or through other variables)");
  for (std::size_t i = 0; i < sim_.atoms.n; ++i) {
    ctx.atom = i;
    out[i] = v.expr->eval_atom(ctx, i);
  }
  return true;
}

std::string Variables::current(const Var& v) {
  if (v.style != "loop") return v.values[v.which];
  std::string s = std::to_string(v.first + static_cast<long>(v.which));
  if (static_cast<int>(s.size()) < v.pad) s = std::string(v.pad - s.size(), '0') + s;
  return s;
}

std::string Variables::fingerprint() const {
  std::string f;
  for (const auto& [name, v] : vars_)
    if (!v.expr) f += name + '\x1f' + current(v) + '\x1e';
  return f;
}

// Evaluates a new formula once with stand-ins for every reference, so that a misspelt
// thermo keyword or per-atom name fails at its own line. c_, f_ and v_ references and
// groups are not checked: a deck may define them after the variable (LIGGGHTS evaluates
// equal-style variables only when they are used).
namespace {
struct NameCheck : ExprContext {
  Simulation& sim;
  std::string unknown;
  explicit NameCheck(Simulation& s) : sim(s) {}
  bool thermo_keyword(const std::string& n, double& out) override {
    if (!sim.thermo->keyword(n, out) && unknown.empty()) unknown = n;
    out = 1.0;
    return true;
  }
  bool variable(const std::string&, double& out) override { return (out = 1.0, true); }
  bool compute_or_fix(char, const std::string&, int, int, double& out) override { return (out = 1.0, true); }
  bool atom_value_by_id(const std::string&, long, double& out) override { return (out = 1.0, true); }
  bool group_function(const std::string&, const std::vector<std::string>&, double& out) override {
    return (out = 1.0, true);
  }
  bool atom_value_local(const std::string& n, std::size_t, double& out) override {
    static Atoms one = [] {
      Atoms a;
      a.resize(1);
      return a;
    }();
    if (n.rfind("v_", 0) == 0 || n.rfind("c_", 0) == 0 || n.rfind("f_", 0) == 0) return false;
    return SimContext::atom_field(one, n, 0, out);
  }
};
}  // namespace

void Variables::check_names(const Args& a, const Expression& e, bool atom_style) {
  NameCheck check(sim_);
  try {
    if (atom_style) e.eval_atom(check, 0);
    else e.eval(check);
  } catch (const ExpressionError&) {
    // stand-in values can divide by zero and the like; only unknown names matter here
  }
  if (!check.unknown.empty())
    a.fail(3, "a formula whose names are known: '" + check.unknown + "' is not a thermo keyword" +
                  (atom_style ? " nor a per-atom value (x, vx, fx, omegax, radius, mass, type, id, ...)" : "") +
                  " (references to computes, fixes and variables are written c_ID, f_ID, v_name)");
}

}  // namespace sable
