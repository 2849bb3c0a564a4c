#pragma once
// LAMMPS/LIGGGHTS formula evaluation for equal-style and atom-style variables,
// immediate $(...) and the "if" command. A formula is parsed once into a small
// AST and evaluated many times against an ExprContext supplied by the engine.
//
// Semantics follow LIGGGHTS' variable.cpp (a LAMMPS 2013-era descendant):
//  * precedence, highest first: unary - and !, ^, * / %, + -, < <= > >=, == !=, &&, || |^
//  * unary minus binds tighter than ^, so -2^2 == 4 (LAMMPS, unlike math convention);
//  * every binary operator, ^ included, is LEFT-associative: 2^3^2 == (2^3)^2 == 64,
//    because LAMMPS' operator stack pops on equal precedence;
//  * && and || evaluate both sides (no short-circuit) as LAMMPS does, which also keeps
//    random() streams identical; comparisons and logicals yield 1.0 or 0.0;
//  * x^0 == 1 (newer LAMMPS; old versions reject it), 0^negative is an error;
//    division or modulo by 0, sqrt of a negative, ln/log of a non-positive value and
//    asin/acos outside [-1,1] are errors naming the formula;
//  * round() rounds halves up (round(-2.5) == -2), like LAMMPS' MYROUND;
//  * random(lo,hi,seed) / normal(mu,sigma,seed) use LAMMPS' Marsaglia generator
//    seeded on first use, so serial LIGGGHTS sequences are reproduced; each parsed
//    formula (and its copies) owns one stream, where LAMMPS shares one stream among
//    all variables. Evaluating a formula that calls them is not thread-safe;
//  * ramp/stagger/logfreq/stride/vdisplace/swiggle/cwiggle read thermo keywords
//    "step", "dt" and, for ramp/vdisplace/swiggle/cwiggle, "beginstep"/"endstep"
//    (the first and last step of the current run) from the context.
// min(a,b)/max(a,b) are the two-argument math functions; LAMMPS' one-argument
// vector reductions sum/min/max/ave/trap, c_ID[i][j] arrays and gmask/rmask are
// not supported and fail with a message saying so.
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace sable {

// Supplies everything an expression can reference. The engine implements it.
struct ExprContext {
  virtual ~ExprContext() = default;
  // thermo keyword such as step, atoms, time, dt, ke, cpu, xlo, xhi, ylo, yhi, zlo, zhi, lx, ly, lz, vol; return false if unknown
  virtual bool thermo_keyword(const std::string& name, double& out) = 0;
  // v_name (equal-style): return false if unknown. v_name[ID] goes to atom_value_by_id("v_name", ID).
  virtual bool variable(const std::string& name, double& out) = 0;
  // c_ID, c_ID[i], f_ID, f_ID[i], f_ID[i][j] (index 0 = scalar; 1-based vector index otherwise;
  // column > 0: element (index, column) of a global array). return false if unknown
  virtual bool compute_or_fix(char kind /*'c' or 'f'*/, const std::string& id, int index, int column, double& out) = 0;
  // per-atom value by atom ID: x[1], vx[2], omegaz[1], fz[3], radius[4], mass[2], type[1] ... name is e.g. "x","vx","omegaz","fz"
  virtual bool atom_value_by_id(const std::string& name, long id, double& out) = 0;
  // group functions: count(g), mass(g), xcm(g,x), vcm(g,y), fcm(g,z), bound(g,xmin) etc.; args are the raw comma-separated words
  virtual bool group_function(const std::string& func, const std::vector<std::string>& args, double& out) = 0;
  // atom-style context: value of per-atom quantity (x, y, z, vx, vy, vz, fx, fy, fz, radius, mass, type, id, omegax...) for
  // atom index i; return false if unknown. eval_atom() also asks it first for "v_name", "c_ID", "c_ID[N]", "f_ID" and
  // "f_ID[N]" so per-atom variables, computes and fixes resolve per atom before falling back to their global values.
  virtual bool atom_value_local(const std::string& name, std::size_t i, double& out) { (void)name; (void)i; (void)out; return false; }
};

class ExpressionError : public std::runtime_error { public: using std::runtime_error::runtime_error; };

// Value of the constant "version" in formulas (LAMMPS reports its release date).
inline constexpr double kExpressionVersion = 20240101;

struct ExprNode;  // private AST node, defined in expression.cpp

// Parses once, evaluates many times. Throws ExpressionError with a message that names the offending token and
// says what was expected, e.g. "unknown function 'sqr' (expected one of sqrt, exp, ...)" or "unknown thermo keyword 'stepz'".
// Copies are cheap and share the parsed tree (and its random() stream).
class Expression {
 public:
  explicit Expression(const std::string& text);   // parse; syntax errors thrown here
  double eval(ExprContext& ctx) const;            // equal-style
  double eval_atom(ExprContext& ctx, std::size_t i) const; // atom-style: bare names like x, vx resolve through atom_value_local first, then thermo keywords
  const std::string& text() const { return text_; }

 private:
  Expression(const std::string& text, bool boolean);
  double run(ExprContext& ctx, const std::size_t* atom) const;
  friend double evaluate_boolean(const std::string& text);
  std::string text_;
  std::shared_ptr<const ExprNode> root_;
};

double evaluate(const std::string& text, ExprContext& ctx); // convenience: parse + eval once (fresh random() stream)

// The "if" command's Boolean: numbers, bare words (letters, digits, _) as strings,
// comparisons, && || ! and parentheses, after ${...}/$(...) substitution. Strings may
// only meet strings with == or != (LAMMPS evaluate_boolean). Returns 1.0 or 0.0 for a
// comparison, the number itself for a lone number.
double evaluate_boolean(const std::string& text);

}  // namespace sable
