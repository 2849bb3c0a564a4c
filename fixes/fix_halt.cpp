// fix ID group halt N attribute operator value [error hard|soft|continue] [message yes|no]
// LAMMPS' fix halt: every N steps, at the end of the step, compare the
// attribute with value; when the condition holds, end the run.
//   attribute  v_name (an equal-style variable) or tlimit (wall seconds since
//              the run's first step; the setup is not counted); LAMMPS' bondmax
//              and diskfree are not supported
//   operator   < <= > >= == != |^ (xor: exactly one of attribute and value is 0)
//   error      hard (default, as LAMMPS): stop the deck with an error naming the
//              step, the condition and the value; soft: end the run (its thermo
//              line at that step), go on with the deck but skip its later runs;
//              continue: end the run, later runs go on from that step
//   message    yes (default): print the condition met
// The group is ignored (as in LAMMPS). A NaN attribute meets no condition but
// != and |^ (LAMMPS, whose tests are negated, would halt on it).
#include <cmath>
#include <cstdio>
#include <string>

#include "core/input/expression.h"
#include "core/engine/simulation.h"
#include "core/input/style_registry.h"
#include "core/input/variable.h"

namespace sable {

class FixHalt : public Fix {
 public:
  FixHalt(Simulation& s, const Args& a) : Fix(s, a) {
    hooks = END_OF_STEP;
    nevery = static_cast<int>(a.integer(4, "the check period N"));
    if (nevery < 1) a.fail(4, "a check period N >= 1");
    const std::string& attr = a.word(5, "v_name or tlimit");
    if (attr.rfind("v_", 0) == 0 && attr.size() > 2) var_ = attr.substr(2);
    else if (attr != "tlimit") a.fail(5, "v_name (an equal-style variable) or tlimit");
    check_variable();
    op_ = a.word(6, "an operator: < <= > >= == != |^");
    if (op_ != "<" && op_ != "<=" && op_ != ">" && op_ != ">=" && op_ != "==" && op_ != "!=" && op_ != "|^")
      a.fail(6, "an operator: < <= > >= == != |^");
    value_ = a.num(7, "the value to compare with");
    if (!std::isfinite(value_)) a.fail(7, "a finite value to compare with");
    for (std::size_t i = 8; i < a.size(); i += 2) {
      if (a[i] == "error") {
        const std::string& e = a.word(i + 1, "hard, soft or continue");
        if (e != "hard" && e != "soft" && e != "continue") a.fail(i + 1, "hard, soft or continue");
        error_ = e;
      } else if (a[i] == "message") {
        message_ = a.yes_no(i + 1, "yes or no");
      } else {
        a.fail(i, "error or message ('path' goes with diskfree, which sable does not support)");
      }
    }
  }

  void init() override { check_variable(); }  // the variable may have been deleted or redefined since
  void setup() override { t_run_ = sim.wall_seconds(); }

  void end_of_step() override {
    const double v = attribute();
    if (!met(v)) return;
    char buf[256];
    std::snprintf(buf, sizeof buf, "fix halt %s: condition %s %s %g met on step %ld with value %.10g", id.c_str(),
                  args[5].c_str(), op_.c_str(), value_, sim.step, v);
    if (error_ == "hard") {
      sim.flush_outputs();
      args.fail_line(std::string(buf) + " (error hard; 'error continue' ends the run and goes on)");
    }
    if (message_) sim.print(buf);
    sim.request_stop(error_ == "soft" ? "fix halt " + id + " ended a run on step " + std::to_string(sim.step) +
                                            " with 'error soft', which skips every later run"
                                      : "");
  }

 private:
  std::string var_, op_, error_ = "hard";
  double value_ = 0, t_run_ = 0;
  bool message_ = true;

  void check_variable() const {
    if (var_.empty()) return;
    if (!sim.variables->exists(var_))
      args.fail(5, "a defined equal-style variable after v_ (no variable '" + var_ + "')");
    if (!sim.variables->is_equal_style(var_))
      args.fail(5, "an equal-style variable after v_ ('" + var_ + "' is another style)");
  }
  double attribute() const {
    if (var_.empty()) return sim.comm.highest(sim.wall_seconds() - t_run_);  // ranks: the slowest's clock
    check_variable();
    double v = 0;
    try {
      sim.variables->numeric(var_, v);
    } catch (const ExpressionError& e) {
      args.fail_line("evaluating v_" + var_ + " on step " + std::to_string(sim.step) + ": " + e.what());
    }
    return v;
  }
  bool met(double v) const {
    if (op_ == "<") return v < value_;
    if (op_ == "<=") return v <= value_;
    if (op_ == ">") return v > value_;
    if (op_ == ">=") return v >= value_;
    if (op_ == "==") return v == value_;
    if (op_ == "!=") return v != value_;
    return (v == 0.0) != (value_ == 0.0);  // |^
  }
};

SABLE_FIX("halt", FixHalt);

}  // namespace sable
