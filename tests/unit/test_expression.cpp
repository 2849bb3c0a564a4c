// Unit tests for core/expression: LAMMPS formula grammar, references through a mock
// context, atom-style evaluation, the "if" Boolean and error messages.
// Tolerances: EXPECT_EQ where the result is exact in binary floating point,
// EXPECT_DOUBLE_EQ (4 ulp) for single libm calls, EXPECT_NEAR with the stated bound otherwise.
#include "core/input/expression.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_expression {

using sable::evaluate;
using sable::evaluate_boolean;
using sable::Expression;
using sable::ExpressionError;

namespace {

// Three atoms, IDs 1..3 stored at local indices 0..2.
struct MockContext : sable::ExprContext {
  std::map<std::string, double> thermo{{"step", 1000}, {"dt", 1e-5}, {"atoms", 3}, {"beginstep", 0}, {"endstep", 2000}};
  std::map<std::string, double> vars{{"b", 2.5}, {"zero", 0}};
  std::map<std::string, double> refs{{"c:t:0", 300}, {"c:t:2", 7}, {"f:f:0", 4}, {"f:f:1", 1.5}, {"f:rb:2:5", -3}};
  std::map<std::string, std::vector<double>> per{{"x", {1, 2, 9}}, {"vx", {0.5, -1, 2}}, {"mass", {1, 2, 3}},
                                                 {"v_pa", {10, 20, 30}}, {"c_pe", {-1, -2, -3}}};
  std::string last_func;
  std::vector<std::string> last_args;

  static bool get(const std::map<std::string, double>& m, const std::string& k, double& out) {
    auto it = m.find(k);
    if (it == m.end()) return false;
    out = it->second;
    return true;
  }
  bool thermo_keyword(const std::string& n, double& out) override { return get(thermo, n, out); }
  bool variable(const std::string& n, double& out) override { return get(vars, n, out); }
  bool compute_or_fix(char kind, const std::string& id, int index, int column, double& out) override {
    return get(refs, std::string(1, kind) + ":" + id + ":" + std::to_string(index) + (column ? ":" + std::to_string(column) : ""), out);
  }
  bool atom_value_by_id(const std::string& n, long id, double& out) override {
    auto it = per.find(n);
    if (it == per.end() || id < 1 || id > 3) return false;
    out = it->second[static_cast<std::size_t>(id - 1)];
    return true;
  }
  bool group_function(const std::string& f, const std::vector<std::string>& args, double& out) override {
    last_func = f;
    last_args = args;
    if (args.empty() || (args[0] != "all" && args[0] != "grains")) return false;
    if (f == "count") out = args[0] == "all" ? 3 : 2;
    else if (f == "mass") out = 6;
    else if (f == "xcm" && args.size() >= 2 && args[1] == "x") out = 4;
    else if (f == "bound" && args.size() == 2 && args[1] == "zmax") out = 9.5;
    else return false;
    return true;
  }
  bool atom_value_local(const std::string& n, std::size_t i, double& out) override {
    auto it = per.find(n);
    if (it == per.end() || i >= it->second.size()) return false;
    out = it->second[i];
    return true;
  }
};

double ev(const std::string& f) {
  MockContext ctx;
  return evaluate(f, ctx);
}

// The message of the ExpressionError thrown by parsing and evaluating f ("" if none).
std::string error_of(const std::string& f) {
  MockContext ctx;
  try {
    evaluate(f, ctx);
  } catch (const ExpressionError& e) {
    return e.what();
  }
  return "";
}

#define EXPECT_ERROR(formula, fragment) \
  EXPECT_NE(error_of(formula).find(fragment), std::string::npos) << "formula: " << (formula) << "\nmessage: " << error_of(formula)

}  // namespace

TEST(Expression, NumbersAndConstants) {
  EXPECT_EQ(ev("42"), 42.0);
  EXPECT_EQ(ev("1e-5"), 1e-5);
  EXPECT_EQ(ev(".5"), 0.5);
  EXPECT_EQ(ev("2."), 2.0);
  EXPECT_EQ(ev("1E+3"), 1000.0);
  EXPECT_EQ(ev("3.5e2"), 350.0);
  EXPECT_EQ(ev("  7  "), 7.0);
  EXPECT_EQ(ev("PI"), std::numbers::pi);
  EXPECT_EQ(ev("version"), sable::kExpressionVersion);
}

TEST(Expression, PrecedenceFollowsLammps) {
  EXPECT_EQ(ev("2+3*4^2"), 50.0);
  // Unary minus binds tighter than ^ in LAMMPS (precedence 8 vs 7): -2^2 == (-2)^2.
  EXPECT_EQ(ev("-2^2"), 4.0);
  EXPECT_EQ(ev("-(2^2)"), -4.0);
  EXPECT_EQ(ev("2^-2"), 0.25);
  EXPECT_EQ(ev("2*-3^2"), 18.0);
  EXPECT_EQ(ev("2--3"), 5.0);
  EXPECT_EQ(ev("10-4-3"), 3.0);
  EXPECT_EQ(ev("8/4/2"), 1.0);
  EXPECT_EQ(ev("2*3%4"), 2.0);
  EXPECT_EQ(ev("7%3"), 1.0);
  EXPECT_EQ(ev("-7%3"), -1.0);  // fmod keeps the dividend's sign, as LAMMPS
  EXPECT_EQ(ev("(2+3)*4"), 20.0);
  EXPECT_EQ(ev("!0+1"), 2.0);    // (!0)+1
  EXPECT_EQ(ev("1+2<4"), 1.0);   // arithmetic before comparison
  EXPECT_EQ(ev("1<2==1"), 1.0);  // comparison before equality
  EXPECT_EQ(ev("1||0&&0"), 1.0); // && before ||
  EXPECT_EQ(ev("0&&1||1"), 1.0);
}

TEST(Expression, PowerIsLeftAssociativeLikeLammps) {
  // LAMMPS' operator stack pops on equal precedence, so ^ groups to the left.
  EXPECT_EQ(ev("2^3^2"), 64.0);
  EXPECT_EQ(ev("(2^3)^2"), 64.0);
  EXPECT_EQ(ev("2^(3^2)"), 512.0);
  EXPECT_EQ(ev("2^-3^2"), 0.015625);  // (2^-3)^2
  EXPECT_EQ(ev("5^0"), 1.0);
  EXPECT_EQ(ev("0^0"), 1.0);
  EXPECT_EQ(ev("9^0.5"), 3.0);
}

TEST(Expression, MathFunctions) {
  const double pi = std::numbers::pi;
  EXPECT_EQ(ev("sqrt(16)"), 4.0);
  EXPECT_EQ(ev("exp(0)"), 1.0);
  EXPECT_NEAR(ev("ln(exp(2))"), 2.0, 1e-15);
  EXPECT_NEAR(ev("log(1000)"), 3.0, 1e-15);
  EXPECT_EQ(ev("abs(-3)"), 3.0);
  EXPECT_NEAR(ev("sin(PI/2)"), 1.0, 1e-15);
  EXPECT_EQ(ev("cos(0)"), 1.0);
  EXPECT_NEAR(ev("tan(PI/4)"), 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(ev("asin(1)"), pi / 2);
  EXPECT_EQ(ev("acos(1)"), 0.0);
  EXPECT_DOUBLE_EQ(ev("atan(1)"), pi / 4);
  EXPECT_DOUBLE_EQ(ev("atan2(1,-1)"), 3 * pi / 4);
  EXPECT_EQ(ev("ceil(1.2)"), 2.0);
  EXPECT_EQ(ev("floor(-1.2)"), -2.0);
  EXPECT_EQ(ev("round(2.5)"), 3.0);
  EXPECT_EQ(ev("round(-2.5)"), -2.0);  // halves round up, LAMMPS MYROUND
  EXPECT_EQ(ev("round(-2.6)"), -3.0);
  EXPECT_EQ(ev("min(3,-1)"), -1.0);
  EXPECT_EQ(ev("max(3, -1)"), 3.0);
  EXPECT_EQ(ev("sqrt(max(16,9))+abs(min(-2,1))"), 6.0);
  EXPECT_EQ(ev("sqrt (4)"), 2.0);
}

TEST(Expression, TimeDependentFunctions) {
  // step 1000, dt 1e-5, run from step 0 to 2000 in the mock
  EXPECT_EQ(ev("ramp(0,10)"), 5.0);
  EXPECT_NEAR(ev("vdisplace(1,2)"), 1.02, 1e-15);
  EXPECT_NEAR(ev("swiggle(0,1,0.04)"), 1.0, 1e-12);  // sin(2pi/0.04 * 0.01) = sin(pi/2)
  EXPECT_NEAR(ev("cwiggle(0,1,0.04)"), 1.0, 1e-12);  // 1 - cos(pi/2)
  EXPECT_EQ(ev("stagger(1000,100)"), 1100.0);
  EXPECT_EQ(ev("logfreq(100,3,10)"), 2000.0);
  EXPECT_EQ(ev("stride(100,5000,300)"), 1300.0);
  EXPECT_EQ(ev("stride(100,1200,300)"), 9.0e18);
}

TEST(Expression, RandomIsDeterministicPerSeed) {
  MockContext ctx;
  Expression a("random(2,5,12345)"), b("random(2,5,12345)"), c("random(2,5,777)");
  double first = a.eval(ctx);
  EXPECT_EQ(first, b.eval(ctx));
  EXPECT_NE(first, c.eval(ctx));
  double second = a.eval(ctx);
  EXPECT_NE(first, second);  // the stream advances between evaluations
  EXPECT_EQ(second, b.eval(ctx));
  for (int i = 0; i < 1000; ++i) {
    double v = a.eval(ctx);
    ASSERT_GE(v, 2.0);
    ASSERT_LT(v, 5.0);
  }
  // normal(): sample mean of 20000 draws within 5 standard errors (5*2/sqrt(20000) = 0.071)
  Expression n("normal(10,2,4242)");
  double sum = 0.0;
  for (int i = 0; i < 20000; ++i) sum += n.eval(ctx);
  EXPECT_NEAR(sum / 20000, 10.0, 0.071);
  EXPECT_EQ(Expression("normal(1,0,5)").eval(ctx), 1.0);
}

TEST(Expression, ComparisonsAndLogicals) {
  EXPECT_EQ(ev("3 > 2"), 1.0);
  EXPECT_EQ(ev("3 >= 3"), 1.0);
  EXPECT_EQ(ev("2 <= 1"), 0.0);
  EXPECT_EQ(ev("2 < 2"), 0.0);
  EXPECT_EQ(ev("2 == 2.0"), 1.0);
  EXPECT_EQ(ev("2 != 2"), 0.0);
  EXPECT_EQ(ev("1 && 0"), 0.0);
  EXPECT_EQ(ev("0 || 2"), 1.0);
  EXPECT_EQ(ev("5 && -3"), 1.0);
  EXPECT_EQ(ev("!5"), 0.0);
  EXPECT_EQ(ev("!!5"), 1.0);
  EXPECT_EQ(ev("1 |^ 1"), 0.0);
  EXPECT_EQ(ev("1 |^ 0"), 1.0);
}

TEST(Expression, References) {
  MockContext ctx;
  EXPECT_EQ(evaluate("2*v_b+sqrt(x[3])", ctx), 8.0);
  EXPECT_NEAR(evaluate("step*dt", ctx), 0.01, 1e-15);
  EXPECT_EQ(evaluate("atoms", ctx), 3.0);
  EXPECT_EQ(evaluate("c_t", ctx), 300.0);
  EXPECT_EQ(evaluate("c_t[2]", ctx), 7.0);
  EXPECT_EQ(evaluate("f_f + f_f[1]", ctx), 5.5);
  EXPECT_EQ(evaluate("f_rb[2][5] * 2", ctx), -6);  // a global array element (fix rigid)
  EXPECT_EQ(evaluate("vx[1+1]", ctx), -1.0);  // the atom ID may be a formula
  EXPECT_EQ(evaluate("mass[3]*2", ctx), 6.0);
  EXPECT_EQ(evaluate("v_pa[2]", ctx), 20.0);  // per-atom variable of atom ID 2
  // values are looked up at evaluation time, not at parse time
  Expression e("v_b*10");
  EXPECT_EQ(e.eval(ctx), 25.0);
  ctx.vars["b"] = 4;
  EXPECT_EQ(e.eval(ctx), 40.0);
  EXPECT_EQ(e.text(), "v_b*10");
  Expression copy = e;
  EXPECT_EQ(copy.eval(ctx), 40.0);
}

TEST(Expression, GroupFunctionsGetRawWords) {
  MockContext ctx;
  EXPECT_EQ(evaluate("xcm(all,x)", ctx), 4.0);
  EXPECT_EQ(ctx.last_func, "xcm");
  EXPECT_EQ(ctx.last_args, (std::vector<std::string>{"all", "x"}));
  EXPECT_EQ(evaluate("count(grains, reg1)", ctx), 2.0);
  EXPECT_EQ(ctx.last_args, (std::vector<std::string>{"grains", "reg1"}));
  EXPECT_EQ(evaluate("2*mass(all)+count(all)", ctx), 15.0);
  EXPECT_EQ(evaluate("bound(all,zmax)", ctx), 9.5);
  EXPECT_EQ(ctx.last_func, "bound");
}

TEST(Expression, AtomStyle) {
  MockContext ctx;
  Expression f("x*2+vx");
  EXPECT_EQ(f.eval_atom(ctx, 0), 2.5);
  EXPECT_EQ(f.eval_atom(ctx, 1), 3.0);
  EXPECT_EQ(f.eval_atom(ctx, 2), 20.0);
  // bare names: per-atom first, thermo keywords second; v_/c_ resolve per atom when the engine has them
  EXPECT_EQ(Expression("mass*step").eval_atom(ctx, 2), 3000.0);
  EXPECT_EQ(Expression("v_pa + c_pe").eval_atom(ctx, 1), 18.0);
  EXPECT_EQ(Expression("v_b + c_t").eval_atom(ctx, 1), 302.5);  // global fall-back
  EXPECT_EQ(Expression("x - x[1]").eval_atom(ctx, 2), 8.0);
  EXPECT_EQ(Expression("x > 1.5").eval_atom(ctx, 0), 0.0);
  EXPECT_EQ(Expression("x > 1.5").eval_atom(ctx, 1), 1.0);
}

TEST(Expression, IfBoolean) {
  EXPECT_EQ(evaluate_boolean("4 > 3"), 1.0);
  EXPECT_EQ(evaluate_boolean("-5 >= -5.0"), 1.0);
  EXPECT_EQ(evaluate_boolean("granular == granular"), 1.0);
  EXPECT_EQ(evaluate_boolean("abc != abd"), 1.0);
  EXPECT_EQ(evaluate_boolean("(yes == no) || (1 < 2 && !(3 < 2))"), 1.0);
  EXPECT_EQ(evaluate_boolean("2.5"), 2.5);
  EXPECT_THROW(evaluate_boolean("abc == 3"), ExpressionError);
  EXPECT_THROW(evaluate_boolean("abc > 1"), ExpressionError);
  EXPECT_THROW(evaluate_boolean("1 = 1"), ExpressionError);
}

TEST(Expression, SyntaxErrorsNameTheToken) {
  EXPECT_ERROR("sqr(2)", "unknown function 'sqr'");
  EXPECT_ERROR("sqr(2)", "expected one of sqrt, exp");
  EXPECT_ERROR("2+*3", "unexpected '*'");
  EXPECT_ERROR("(1+2", "expected ')'");
  EXPECT_ERROR("2 3", "unexpected '3'");
  EXPECT_ERROR("3 = 3", "unexpected '='");
  EXPECT_ERROR("1+", "formula ends too early");
  EXPECT_ERROR("", "formula ends too early");
  EXPECT_ERROR("atan2(1)", "function 'atan2' takes 2 argument(s), got 1");
  EXPECT_ERROR("c_t[0]", "bad index '0' for c_t");
  EXPECT_ERROR("c_t[1][2]", "no global array element [1][2]");
  EXPECT_ERROR("1.2e", "malformed exponent");
  EXPECT_ERROR("count()", "empty argument in count()");
  EXPECT_ERROR("2 $ 3", "'$'");
  EXPECT_ERROR("sqr(2)", "in formula 'sqr(2)'");
}

TEST(Expression, EvaluationErrorsNameTheCause) {
  EXPECT_ERROR("stepz+1", "unknown thermo keyword 'stepz'");
  EXPECT_ERROR("1/(v_b-2.5)", "division by zero in formula '1/(v_b-2.5)'");
  EXPECT_ERROR("5%v_zero", "modulo by zero");
  EXPECT_ERROR("0^-1", "zero raised to a negative power");
  EXPECT_ERROR("sqrt(-1)", "sqrt(): square root of negative value");
  EXPECT_ERROR("ln(0)", "ln(): log of zero/negative value");
  EXPECT_ERROR("asin(2)", "asin(): argument outside [-1,1]");
  EXPECT_ERROR("v_nope", "unknown variable 'nope'");
  EXPECT_ERROR("c_zz", "unknown compute reference 'c_zz'");
  EXPECT_ERROR("f_f[9]", "unknown fix reference 'f_f[9]'");
  EXPECT_ERROR("x+1", "per-atom quantity 'x' needs an atom ID");
  EXPECT_ERROR("x[1.5]", "must be a positive integer");
  EXPECT_ERROR("x[7]", "no value for x[7]");
  EXPECT_ERROR("density[1]", "unknown per-atom quantity 'density'");
  EXPECT_ERROR("xcm(nogroup,x)", "group function xcm(nogroup,x) failed");
  EXPECT_ERROR("random(0,1,0)", "random seed 0 out of range");
  EXPECT_ERROR("normal(0,-1,5)", "normal(): sigma must be >= 0");
  MockContext ctx;
  ctx.thermo.erase("beginstep");
  EXPECT_THROW(evaluate("ramp(0,1)", ctx), ExpressionError);
  try {
    Expression("y+1").eval_atom(ctx, 0);
    FAIL() << "expected an error";
  } catch (const ExpressionError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown per-atom quantity or thermo keyword 'y'"), std::string::npos) << e.what();
  }
}

}  // namespace test_expression
