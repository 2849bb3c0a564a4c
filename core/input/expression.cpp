// Recursive-descent parser for LAMMPS formulas; semantics documented in expression.h.
#include "core/input/expression.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <numbers>
#include <string_view>

#include "core/engine/random.h"

namespace sable {
namespace {

// LAMMPS' RanMars (Marsaglia RANMAR + polar Box-Muller), kept bit-for-bit so that
// random()/normal() reproduce serial LIGGGHTS runs for the same seed.
class RanMars {
 public:
  explicit RanMars(int seed) {
    if (seed <= 0 || seed > 900000000)
      throw ExpressionError("random seed " + std::to_string(seed) + " out of range (expected 1..900000000)");
    int ij = (seed - 1) / 30082, kl = (seed - 1) - 30082 * ij;
    int i = (ij / 177) % 177 + 2, j = ij % 177 + 2, k = (kl / 169) % 178 + 1, l = kl % 169;
    for (int ii = 1; ii <= 97; ii++) {
      double s = 0.0, t = 0.5;
      for (int jj = 1; jj <= 24; jj++) {
        int m = ((i * j) % 179) * k % 179;
        i = j; j = k; k = m;
        l = (53 * l + 1) % 169;
        if ((l * m) % 64 >= 32) s += t;
        t *= 0.5;
      }
      u_[ii] = s;
    }
    uniform();
  }
  double uniform() {
    double uni = u_[i97_] - u_[j97_];
    if (uni < 0.0) uni += 1.0;
    u_[i97_] = uni;
    if (--i97_ == 0) i97_ = 97;
    if (--j97_ == 0) j97_ = 97;
    c_ -= cd_;
    if (c_ < 0.0) c_ += cm_;
    uni -= c_;
    if (uni < 0.0) uni += 1.0;
    return uni;
  }
  double gaussian() {
    if (save_) { save_ = false; return second_; }
    double g;
    polar_gaussians([this] { return uniform(); }, second_, g);  // LAMMPS keeps the first for the next call
    save_ = true;
    return g;
  }

 private:
  double u_[98] = {};
  int i97_ = 97, j97_ = 33;
  double c_ = 362436.0 / 16777216.0, cd_ = 7654321.0 / 16777216.0, cm_ = 16777213.0 / 16777216.0;
  bool save_ = false;
  double second_ = 0.0;
};

enum class Op { Num, Str, Neg, Not, Or, Xor, And, Eq, Ne, Lt, Le, Gt, Ge, Add, Sub, Mul, Div, Mod, Pow,
                Func, Group, Thermo, Var, Ref, AtomById };

// Math functions; order matches enum Fn.
enum Fn { Sqrt, Exp, Ln, Log, Abs, Sin, Cos, Tan, Asin, Acos, Atan, Atan2, Ceil, Floor, Round, Min, Max,
          Random, Normal, Ramp, Stagger, Logfreq, Stride, Vdisplace, Swiggle, Cwiggle };
struct FnInfo { std::string_view name; int nargs; };
constexpr FnInfo kFns[] = {{"sqrt", 1}, {"exp", 1}, {"ln", 1}, {"log", 1}, {"abs", 1}, {"sin", 1}, {"cos", 1},
    {"tan", 1}, {"asin", 1}, {"acos", 1}, {"atan", 1}, {"atan2", 2}, {"ceil", 1}, {"floor", 1}, {"round", 1},
    {"min", 2}, {"max", 2}, {"random", 3}, {"normal", 3}, {"ramp", 2}, {"stagger", 2}, {"logfreq", 3},
    {"stride", 3}, {"vdisplace", 2}, {"swiggle", 3}, {"cwiggle", 3}};
constexpr std::string_view kGroupFns[] = {"count", "mass", "charge", "xcm", "vcm", "fcm", "bound", "gyration",
    "ke", "angmom", "torque", "inertia", "omega"};
constexpr std::string_view kAtomNames[] = {"x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz", "omegax", "omegay",
    "omegaz", "tqx", "tqy", "tqz", "radius", "mass", "type", "id"};

template <class Range, class Get>
std::string join(const Range& r, Get get) {
  std::string s;
  for (const auto& e : r) s += (s.empty() ? "" : ", ") + std::string(get(e));
  return s;
}

}  // namespace

struct ExprNode {
  Op op = Op::Num;
  double value = 0.0;
  int fn = 0;                      // Func: index into kFns; Ref: vector index (0 = scalar)
  int fn2 = 0;                     // Ref: array column (0 = not an array element)
  int height = 1;                  // levels below and including this node (recursion bound)
  char kind = 0;                   // Ref: 'c' or 'f'
  std::string name;                // full token as written (v_a, c_t[2], x, xcm(all,x)): messages, local lookup
  std::string id;                  // bare name passed to the context (a, t, x, xcm)
  std::vector<std::string> words;  // Group: raw arguments
  std::vector<std::unique_ptr<ExprNode>> kids;
  mutable std::unique_ptr<RanMars> rng;  // random()/normal(): created on first evaluation, as in LAMMPS
};

namespace {

using NodeP = std::unique_ptr<ExprNode>;

// Parsing, evaluating and freeing a tree recurse once per level: a deeper formula
// (100 000 parentheses, or a chain of 100 000 '+') would overflow the stack. One level
// of parentheses costs about ten parser frames; 500 levels overflowed 8 MB under ASan.
constexpr int kMaxFormulaDepth = 128;

NodeP make(Op op, std::vector<NodeP> kids = {}) {
  auto n = std::make_unique<ExprNode>();
  n->op = op;
  for (const NodeP& k : kids) n->height = std::max(n->height, k->height + 1);
  if (n->height > kMaxFormulaDepth)
    throw ExpressionError("formula nested too deeply (more than " + std::to_string(kMaxFormulaDepth) +
                          " levels of parentheses, operators or function calls)");
  n->kids = std::move(kids);
  return n;
}

bool is_word(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

class Parser {
 public:
  Parser(const std::string& s, bool boolean) : s_(s), boolean_(boolean) {}

  NodeP parse() {
    NodeP n = binary(0);
    if (skip() < s_.size()) fail("unexpected " + token(), "an operator or the end of the formula");
    return n;
  }

 private:
  const std::string& s_;
  bool boolean_;
  std::size_t p_ = 0;
  int depth_ = 0;  // unary() calls under way: every nesting passes through it

  std::size_t skip() {
    while (p_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[p_]))) ++p_;
    return p_;
  }
  std::string token() const {
    if (p_ >= s_.size()) return "end of formula";
    std::size_t e = p_ + 1;
    if (is_word(s_[p_])) while (e < s_.size() && is_word(s_[e])) ++e;
    return "'" + s_.substr(p_, e - p_) + "'";
  }
  [[noreturn]] void fail(const std::string& what, const std::string& expected) const {
    throw ExpressionError(what + " at position " + std::to_string(p_ + 1) + " in formula '" + s_ +
                          "' (expected " + expected + ")");
  }
  bool eat(std::string_view t) {
    skip();
    if (s_.compare(p_, t.size(), t) != 0) return false;
    // a lone '!' or '<' must not swallow the first half of '!=' or '<='
    if (t.size() == 1 && p_ + 1 < s_.size() && s_[p_ + 1] == '=' && (t == "!" || t == "<" || t == ">")) return false;
    p_ += t.size();
    return true;
  }
  void expect(char c, const std::string& what) {
    if (!eat(std::string_view(&c, 1))) fail("unexpected " + token(), what);
  }

  // Levels from lowest precedence up; all left-associative, as LAMMPS' operator stack is.
  NodeP binary(int level) {
    struct Tok { std::string_view t; Op op; };
    static const std::vector<std::vector<Tok>> levels = {
        {{"||", Op::Or}, {"|^", Op::Xor}}, {{"&&", Op::And}}, {{"==", Op::Eq}, {"!=", Op::Ne}},
        {{"<=", Op::Le}, {">=", Op::Ge}, {"<", Op::Lt}, {">", Op::Gt}}, {{"+", Op::Add}, {"-", Op::Sub}},
        {{"*", Op::Mul}, {"/", Op::Div}, {"%", Op::Mod}}, {{"^", Op::Pow}}};
    if (level == static_cast<int>(levels.size())) return unary();
    NodeP lhs = binary(level + 1);
    for (bool more = true; more;) {
      more = false;
      for (const Tok& tk : levels[level])
        if (eat(tk.t)) {
          std::vector<NodeP> k;
          k.push_back(std::move(lhs));
          k.push_back(binary(level + 1));
          lhs = make(tk.op, std::move(k));
          more = true;
          break;
        }
    }
    return lhs;
  }

  // Unary operators bind tighter than ^ (LAMMPS precedence 8 vs 7): -2^2 == 4.
  NodeP unary() {
    struct Depth {
      int& d;
      ~Depth() { --d; }
    } guard{++depth_};
    if (depth_ > kMaxFormulaDepth) fail("formula nested too deeply", "at most " + std::to_string(kMaxFormulaDepth) + " levels of parentheses");
    if (eat("-")) { std::vector<NodeP> k; k.push_back(unary()); return make(Op::Neg, std::move(k)); }
    if (eat("!")) { std::vector<NodeP> k; k.push_back(unary()); return make(Op::Not, std::move(k)); }
    if (eat("+")) return unary();
    return primary();
  }

  NodeP number() {
    std::size_t b = p_, digits = 0;
    while (p_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[p_]))) ++p_, ++digits;
    if (p_ < s_.size() && s_[p_] == '.') ++p_;
    while (p_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[p_]))) ++p_, ++digits;
    if (digits == 0) { p_ = b; fail("malformed number " + token(), "digits"); }
    if (p_ < s_.size() && (s_[p_] == 'e' || s_[p_] == 'E')) {
      std::size_t q = p_ + 1;
      if (q < s_.size() && (s_[q] == '+' || s_[q] == '-')) ++q;
      if (q >= s_.size() || !std::isdigit(static_cast<unsigned char>(s_[q]))) { p_ = q; fail("malformed exponent", "digits after 'e'"); }
      while (q < s_.size() && std::isdigit(static_cast<unsigned char>(s_[q]))) ++q;
      p_ = q;
    }
    NodeP n = make(Op::Num);
    n->value = std::strtod(s_.substr(b, p_ - b).c_str(), nullptr);
    return n;
  }

  // Contents of [...] after a name: an expression for atom IDs, a literal integer for c_/f_.
  int int_in_brackets(const std::string& name) {
    skip();
    std::size_t b = p_;
    while (p_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[p_]))) ++p_;
    int v = p_ > b ? std::atoi(s_.substr(b, p_ - b).c_str()) : 0;
    if (v < 1) { p_ = b; fail("bad index " + token() + " for " + name, "a positive integer such as " + name + "[1]"); }
    expect(']', "']' closing " + name + "[");
    return v;
  }

  NodeP call(const std::string& w, std::size_t start) {
    for (std::string_view g : kGroupFns)
      if (w == g) {  // group functions take raw words (group ID, dim, region ID), not formulas
        std::size_t b = p_;
        int depth = 0;
        while (p_ < s_.size() && (depth > 0 || s_[p_] != ')')) depth += (s_[p_] == '(') - (s_[p_] == ')'), ++p_;
        if (p_ >= s_.size()) fail("unterminated " + w + "(", "')'");
        NodeP n = make(Op::Group);
        std::string raw = s_.substr(b, p_ - b), cur;
        for (char c : raw + ",") {
          if (c != ',') { if (!std::isspace(static_cast<unsigned char>(c))) cur += c; continue; }
          if (cur.empty()) { p_ = b; fail("empty argument in " + w + "(" + raw + ")", "a group ID and its arguments"); }
          n->words.push_back(std::move(cur));
          cur.clear();
        }
        ++p_;
        n->id = w;
        n->name = w + "(" + raw + ")";
        return n;
      }
    for (std::size_t f = 0; f < std::size(kFns); ++f)
      if (w == kFns[f].name) {
        NodeP n = make(Op::Func);
        n->fn = static_cast<int>(f);
        n->name = w;
        if (!eat(")")) do n->kids.push_back(binary(0)); while (eat(","));
        if (static_cast<int>(n->kids.size()) != kFns[f].nargs)
          fail("function '" + w + "' takes " + std::to_string(kFns[f].nargs) + " argument(s), got " +
                   std::to_string(n->kids.size()), std::to_string(kFns[f].nargs) + " comma-separated arguments");
        if (!n->kids.empty()) expect(')', "')' closing " + w + "(");
        return n;
      }
    p_ = start;
    fail("unknown function '" + w + "'", "one of " + join(kFns, [](const FnInfo& f) { return f.name; }) +
             " or group functions " + join(kGroupFns, [](std::string_view g) { return g; }));
  }

  NodeP primary() {
    skip();
    if (p_ >= s_.size()) fail("formula ends too early", "a number, name or '('");
    char c = s_[p_];
    if (eat("(")) { NodeP n = binary(0); expect(')', "')'"); return n; }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (!std::isalpha(static_cast<unsigned char>(c))) fail("unexpected " + token(), "a number, name or '('");
    std::size_t b = p_;
    while (p_ < s_.size() && is_word(s_[p_])) ++p_;
    std::string w = s_.substr(b, p_ - b);
    if (boolean_) { NodeP n = make(Op::Str); n->name = w; return n; }  // "if": bare words are strings
    if (eat("(")) return call(w, b);
    NodeP n;
    if (w == "PI" || w == "version") {
      n = make(Op::Num);
      n->value = w == "PI" ? std::numbers::pi : kExpressionVersion;
    } else if (w.size() > 2 && w[1] == '_' && (w[0] == 'c' || w[0] == 'f')) {
      n = make(Op::Ref);
      n->kind = w[0];
      n->id = w.substr(2);
      n->name = w;
      if (eat("[")) {
        n->fn = int_in_brackets(w);
        n->name += "[" + std::to_string(n->fn) + "]";
        if (eat("[")) {  // f_ID[i][j]: a global array element
          n->fn2 = int_in_brackets(w);
          n->name += "[" + std::to_string(n->fn2) + "]";
        }
      }
    } else if (eat("[")) {  // x[ID], v_name[ID]: per-atom value of the atom with this ID
      n = make(Op::AtomById);
      n->id = w;
      n->name = w;
      n->kids.push_back(binary(0));
      expect(']', "']' closing " + w + "[");
    } else if (w.size() > 2 && w[0] == 'v' && w[1] == '_') {
      n = make(Op::Var);
      n->id = w.substr(2);
      n->name = w;
    } else {
      n = make(Op::Thermo);
      n->id = n->name = w;
    }
    return n;
  }
};

struct Evaluator {
  ExprContext& ctx;
  const std::size_t* atom;  // null for equal-style

  [[noreturn]] static void err(const std::string& m) { throw ExpressionError(m); }
  bool local(const std::string& name, double& v) const { return atom && ctx.atom_value_local(name, *atom, v); }
  double keyword(const char* k, const ExprNode& n) const {
    double v;
    if (!ctx.thermo_keyword(k, v)) err(n.name + "() needs thermo keyword '" + k + "', which the engine does not provide");
    return v;
  }

  double operator()(const ExprNode& n) const {
    auto k = [&](std::size_t i) { return (*this)(*n.kids[i]); };
    auto b = [](bool x) { return x ? 1.0 : 0.0; };
    double v = 0.0;
    switch (n.op) {
      case Op::Num: return n.value;
      case Op::Str: err("string '" + n.name + "' can only be compared with == or != to another string");
      case Op::Neg: return -k(0);
      case Op::Not: return b(k(0) == 0.0);
      case Op::Eq: case Op::Ne: {
        bool s0 = n.kids[0]->op == Op::Str, s1 = n.kids[1]->op == Op::Str;
        if (s0 != s1) err("cannot compare string '" + n.kids[s0 ? 0 : 1]->name + "' with a number");
        bool eq = s0 ? n.kids[0]->name == n.kids[1]->name : k(0) == k(1);
        return b(eq == (n.op == Op::Eq));
      }
      default: break;
    }
    if (n.op >= Op::Or && n.op <= Op::Pow) {
      double x = k(0), y = k(1);  // both sides always evaluated, as in LAMMPS
      switch (n.op) {
        case Op::Or: return b(x != 0.0 || y != 0.0);
        case Op::Xor: return b((x != 0.0) != (y != 0.0));
        case Op::And: return b(x != 0.0 && y != 0.0);
        case Op::Lt: return b(x < y);
        case Op::Le: return b(x <= y);
        case Op::Gt: return b(x > y);
        case Op::Ge: return b(x >= y);
        case Op::Add: return x + y;
        case Op::Sub: return x - y;
        case Op::Mul: return x * y;
        case Op::Div: if (y == 0.0) err("division by zero"); return x / y;
        case Op::Mod: if (y == 0.0) err("modulo by zero"); return std::fmod(x, y);
        default:
          if (y == 0.0) return 1.0;
          if (x == 0.0 && y < 0.0) err("zero raised to a negative power");
          return std::pow(x, y);
      }
    }
    switch (n.op) {
      case Op::Thermo:
        if (local(n.id, v) || ctx.thermo_keyword(n.id, v)) return v;
        for (std::string_view a : kAtomNames)
          if (!atom && n.id == a) err("per-atom quantity '" + n.id + "' needs an atom ID in an equal-style formula (expected e.g. " + n.id + "[1])");
        err(std::string(atom ? "unknown per-atom quantity or thermo keyword '" : "unknown thermo keyword '") + n.id + "'");
      case Op::Var:
        if (local(n.name, v) || ctx.variable(n.id, v)) return v;
        err("unknown variable '" + n.id + "' (referenced as " + n.name + ")");
      case Op::Ref:
        if (local(n.name, v) || ctx.compute_or_fix(n.kind, n.id, n.fn, n.fn2, v)) return v;
        err(std::string("unknown ") + (n.kind == 'c' ? "compute" : "fix") + " reference '" + n.name +
            (n.fn2 ? "' (no such ID, or it has no global array element [" + std::to_string(n.fn) + "][" + std::to_string(n.fn2) + "])"
             : n.fn ? "' (no such ID, or it has no vector element " + std::to_string(n.fn) + ")" : "' (no such ID, or it has no global scalar)"));
      case Op::AtomById: {
        double x = k(0);
        if (!(x >= 1.0) || x != std::floor(x) || x > 9.0e18) err("atom ID in " + n.id + "[...] must be a positive integer, got " + std::to_string(x));
        long id = static_cast<long>(x);
        if (ctx.atom_value_by_id(n.id, id, v)) return v;
        err("no value for " + n.id + "[" + std::to_string(id) + "] (unknown per-atom quantity '" + n.id +
            "' or no atom with ID " + std::to_string(id) + "; expected one of " + join(kAtomNames, [](std::string_view a) { return a; }) + ")");
      }
      case Op::Group:
        if (ctx.group_function(n.id, n.words, v)) return v;
        err("group function " + n.name + " failed (unknown group or region, or bad argument)");
      default: return func(n);
    }
  }

  double func(const ExprNode& n) const {
    double a[3] = {0.0, 0.0, 0.0};
    for (std::size_t i = 0; i < n.kids.size(); ++i) a[i] = (*this)(*n.kids[i]);
    auto bad = [&](const std::string& why) { err(n.name + "(): " + why); };
    auto ramp_delta = [&] { return keyword("step", n) - keyword("beginstep", n); };
    switch (static_cast<Fn>(n.fn)) {
      case Sqrt: if (a[0] < 0.0) bad("square root of negative value " + std::to_string(a[0])); return std::sqrt(a[0]);
      case Exp: return std::exp(a[0]);
      case Ln: if (a[0] <= 0.0) bad("log of zero/negative value " + std::to_string(a[0])); return std::log(a[0]);
      case Log: if (a[0] <= 0.0) bad("log of zero/negative value " + std::to_string(a[0])); return std::log10(a[0]);
      case Abs: return std::fabs(a[0]);
      case Sin: return std::sin(a[0]);
      case Cos: return std::cos(a[0]);
      case Tan: return std::tan(a[0]);
      case Asin: if (a[0] < -1.0 || a[0] > 1.0) bad("argument outside [-1,1]"); return std::asin(a[0]);
      case Acos: if (a[0] < -1.0 || a[0] > 1.0) bad("argument outside [-1,1]"); return std::acos(a[0]);
      case Atan: return std::atan(a[0]);
      case Atan2: return std::atan2(a[0], a[1]);
      case Ceil: return std::ceil(a[0]);
      case Floor: return std::floor(a[0]);
      case Round: return a[0] - std::floor(a[0]) >= 0.5 ? std::ceil(a[0]) : std::floor(a[0]);
      case Min: return std::fmin(a[0], a[1]);
      case Max: return std::fmax(a[0], a[1]);
      case Random: case Normal:
        if (n.fn == Normal && a[1] < 0.0) bad("sigma must be >= 0");
        if (!n.rng) n.rng = std::make_unique<RanMars>(static_cast<int>(a[2]));
        return n.fn == Random ? a[0] + n.rng->uniform() * (a[1] - a[0]) : a[0] + a[1] * n.rng->gaussian();
      case Ramp: {
        double d = ramp_delta(), span = keyword("endstep", n) - keyword("beginstep", n);
        if (d != 0.0) d /= span;
        return a[0] + d * (a[1] - a[0]);
      }
      case Stagger: {
        long long x = static_cast<long long>(a[0]), y = static_cast<long long>(a[1]);
        auto step = static_cast<long long>(keyword("step", n));
        if (x <= 0 || y <= 0 || x <= y) bad("expected 0 < y < x");
        long long lower = step / x * x;
        return static_cast<double>(step - lower < y ? lower + y : lower + x);
      }
      case Logfreq: {
        long long x = static_cast<long long>(a[0]), y = static_cast<long long>(a[1]), z = static_cast<long long>(a[2]);
        auto step = static_cast<long long>(keyword("step", n));
        if (x <= 0 || y <= 0 || z <= 0 || y >= z) bad("expected positive x, y, z with y < z");
        if (step < x) return static_cast<double>(x);
        long long lower = x;
        while (step >= z * lower) lower *= z;
        long long multiple = step / lower;
        return static_cast<double>(multiple < y ? (multiple + 1) * lower : lower * z);
      }
      case Stride: {
        long long x = static_cast<long long>(a[0]), y = static_cast<long long>(a[1]), z = static_cast<long long>(a[2]);
        auto step = static_cast<long long>(keyword("step", n));
        if (x < 0 || y < 0 || z <= 0 || x > y) bad("expected 0 <= x <= y and z > 0");
        if (step < x) return static_cast<double>(x);
        if (step >= y) return 9.0e18;
        double next = static_cast<double>(x + (step - x) / z * z + z);
        return next > static_cast<double>(y) ? 9.0e18 : next;
      }
      case Vdisplace: return a[0] + a[1] * ramp_delta() * keyword("dt", n);
      case Swiggle: case Cwiggle: {
        if (a[2] == 0.0) bad("period must be non-zero");
        double arg = 2.0 * std::numbers::pi / a[2] * ramp_delta() * keyword("dt", n);
        return a[0] + a[1] * (n.fn == Swiggle ? std::sin(arg) : 1.0 - std::cos(arg));
      }
    }
    return 0.0;
  }
};

struct NoContext : ExprContext {  // "if" Booleans reference nothing
  bool thermo_keyword(const std::string&, double&) override { return false; }
  bool variable(const std::string&, double&) override { return false; }
  bool compute_or_fix(char, const std::string&, int, int, double&) override { return false; }
  bool atom_value_by_id(const std::string&, long, double&) override { return false; }
  bool group_function(const std::string&, const std::vector<std::string>&, double&) override { return false; }
};

}  // namespace

Expression::Expression(const std::string& text) : Expression(text, false) {}
Expression::Expression(const std::string& text, bool boolean)
    : text_(text), root_(Parser(text_, boolean).parse()) {}

double Expression::run(ExprContext& ctx, const std::size_t* atom) const {
  try {
    return Evaluator{ctx, atom}(*root_);
  } catch (const ExpressionError& e) {  // name the formula; nested v_ references add their own
    throw ExpressionError(std::string(e.what()) + " in formula '" + text_ + "'");
  }
}

double Expression::eval(ExprContext& ctx) const { return run(ctx, nullptr); }
double Expression::eval_atom(ExprContext& ctx, std::size_t i) const { return run(ctx, &i); }

double evaluate(const std::string& text, ExprContext& ctx) { return Expression(text).eval(ctx); }

double evaluate_boolean(const std::string& text) {
  NoContext none;
  return Expression(text, true).run(none, nullptr);
}

}  // namespace sable
