// sable-analyze: command-line front end of the analysis library (README.md next to it).
#include <gsl/gsl_interp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <set>

#include "reference_runs/analysis/analysis.h"

using namespace sable::analysis;

namespace {

struct Cli {
  std::string sub;
  std::vector<std::string> pos;
  std::map<std::string, std::string> opt;
  std::set<std::string> flags;

  bool has(const std::string& k) const { return opt.count(k) > 0; }
  std::string str(const std::string& k, const std::string& def = "") const { return has(k) ? opt.at(k) : def; }
  double num(const std::string& k, double def) const {
    if (!has(k)) return def;
    char* end = nullptr;
    const double v = std::strtod(opt.at(k).c_str(), &end);
    if (!end || *end || opt.at(k).empty()) throw Error(k + ": '" + opt.at(k) + "' is not a number");
    return v;
  }
  std::size_t count(const std::string& k, std::size_t def) const {
    const double v = num(k, double(def));
    if (!(v >= 0) || v != std::floor(v)) throw Error(k + ": '" + opt.at(k) + "' is not a whole number >= 0");
    return static_cast<std::size_t>(v);
  }
  bool flag(const std::string& k) const { return flags.count(k) > 0; }
};

struct Sub {
  const char* name;
  const char* usage;
  const char* help;
  std::vector<std::string> valued, switches;
  std::size_t min_pos, max_pos;
  int (*run)(const Cli&);
};

const char* kReadOpts =
    "  --column C     column: 1-based number or name (fix ave/time header, dump ITEM: ATOMS,\n"
    "                 HDF5 'columns' attribute, CSV header)\n"
    "  --dataset D    HDF5 dataset (default 'values', what fix ave/time writes)\n"
    "  --skip N       drop the first N values (transient)\n";

Vec input(const Cli& c, const std::string& path, const std::string& col_opt = "--column", std::string* label = nullptr) {
  Column col = read_column(path, c.str(col_opt), c.str("--dataset"));
  const std::size_t skip = c.count("--skip", 0);
  if (skip >= col.values.size())
    throw Error(col.label + ": --skip " + std::to_string(skip) + " leaves nothing of " + std::to_string(col.values.size()) + " values");
  for (std::size_t i = 0; i < col.values.size(); ++i)
    if (!std::isfinite(col.values[i])) throw Error(col.label + ": value " + std::to_string(i + 1) + " is not finite");
  if (label) *label = col.label;
  return Vec(col.values.begin() + static_cast<long>(skip), col.values.end());
}

void out_or_print(const Cli& c, const Table& t, const std::string& key = "--out") {
  if (c.has(key)) {
    write_table(c.str(key), t);
    std::printf("wrote %s\n", c.str(key).c_str());
  }
}

std::string ci_text(const Param& p) {
  if (std::isnan(p.ci.lo)) return "(derived)";
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%s%.6g, %.6g%s]", p.ci.lo_open ? "open " : "", p.ci.lo, p.ci.hi,
                p.ci.hi_open ? " open" : "");
  return buf;
}

void print_fit(const Fit& f, const char* title) {
  std::printf("%s: loglik %.6f  AIC %.4f  KS D %.5f (5%% critical %.5f, p %.3g)\n", title, f.loglik, f.aic, f.ks.d,
              f.ks.critical, f.ks.p);
  for (auto& p : f.params) std::printf("  %-8s %.6g  95%% profile %s\n", p.name.c_str(), p.value, ci_text(p).c_str());
}

void add_params(Table& t, const Fit& f, const std::string& prefix) {
  for (auto& p : f.params) {
    t.names.push_back(prefix + p.name);
    t.cols.push_back({p.value});
    t.names.push_back(prefix + p.name + "_lo");
    t.cols.push_back({p.ci.lo});
    t.names.push_back(prefix + p.name + "_hi");
    t.cols.push_back({p.ci.hi});
  }
  for (auto [n, v] : {std::pair{"loglik", f.loglik}, {"aic", f.aic}, {"ks_d", f.ks.d}, {"ks_p", f.ks.p}}) {
    t.names.push_back(prefix + n);
    t.cols.push_back({v});
  }
}

Vec normalised(const Cli& c, const Vec& x, double& mean) {
  mean = c.flag("--raw") ? 1.0 : mean_of(x);
  if (!(mean > 0)) throw Error("cannot normalise by the mean " + std::to_string(mean) + " (use --raw)");
  Vec y;
  for (double v : x) y.push_back(v / mean);
  return y;
}

Histogram hist_of(const Cli& c, const Vec& x) {
  const std::string bins = c.str("--bins", "lin");
  if (bins != "lin" && bins != "log") throw Error("--bins: 'lin' or 'log', not '" + bins + "'");
  return histogram(x, static_cast<int>(c.count("--nbins", 50)), bins == "log", !c.flag("--raw"), c.num("--lo", 0),
                   c.num("--hi", 0));
}

Table hist_table(const Histogram& h, const std::string& label) {
  Table t;
  Vec lo(h.edges.begin(), h.edges.end() - 1), hi(h.edges.begin() + 1, h.edges.end());
  t.names = {"x_lo", "x_hi", "x", "count", "pdf"};
  t.cols = {lo, hi, h.centres, h.counts, h.pdf};
  t.meta = {{"source", label}, {"mean", std::to_string(h.mean)}, {"n", std::to_string(h.n)},
            {"outside", std::to_string(h.outside)}, {"x", "value / mean (bin centre; geometric for log bins)"},
            {"pdf", "count / (n width)"}};
  return t;
}

int cmd_pdf(const Cli& c) {
  std::string label;
  const Vec x = input(c, c.pos[0], "--column", &label);
  const Histogram h = hist_of(c, x);
  std::printf("%s: %zu values divided by %.6g (%s), %zu outside the bins\n", label.c_str(), h.n, h.mean, c.flag("--raw") ? "--raw" : "their mean", h.outside);
  const Table t = hist_table(h, label);
  if (!c.has("--out"))
    for (std::size_t i = 0; i < h.pdf.size(); ++i) std::printf("%.6g %.6g %g\n", h.centres[i], h.pdf[i], h.counts[i]);
  out_or_print(c, t);
  return 0;
}

int cmd_fit_lognormal(const Cli& c) {
  std::string label;
  double mean;
  const Vec x = normalised(c, input(c, c.pos[0], "--column", &label), mean);
  const LogNormalFit f = fit_truncated_lognormal(x);
  std::printf("%s: %zu values divided by their mean %.6g\n", label.c_str(), x.size(), mean);
  print_fit(f.eq7, "Eq. 7 truncated log-normal (mu, sigma, x0)");
  print_fit(f.normal, "truncated normal (m, s), the Gaussian limit");
  std::printf("log-likelihood gain of Eq. 7 over its Gaussian limit: %.4f (limit if < 1.92)\n", f.eq7.loglik - f.normal.loglik);
  if (f.gaussian_limit) std::printf("GAUSSIAN LIMIT: x0 -> inf is inside the 95 %% region; report the truncated normal\n");
  Table t;
  t.meta = {{"source", label}, {"mean", std::to_string(mean)}, {"model", "kneib2017 Eq. 7; normal_*: truncated normal"}};
  t.names = {"n", "gaussian_limit"};
  t.cols = {{double(x.size())}, {f.gaussian_limit ? 1.0 : 0.0}};
  add_params(t, f.eq7, "");
  add_params(t, f.normal, "normal_");
  out_or_print(c, t);
  if (c.has("--curve")) {
    Histogram h = histogram(x, static_cast<int>(c.count("--nbins", 40)), c.str("--bins", "lin") == "log", false);
    Table k = hist_table(h, label);
    Vec e7, nn, best;
    for (double v : h.centres) {
      e7.push_back(f.eq7.pdf(v));
      nn.push_back(f.normal.pdf(v));
      best.push_back(f.gaussian_limit ? nn.back() : e7.back());
    }
    k.names.insert(k.names.end(), {"eq7", "normal", "fit"});
    k.cols.insert(k.cols.end(), {e7, nn, best});
    k.meta.push_back({"gaussian_limit", f.gaussian_limit ? "1" : "0"});
    k.meta[1].second = std::to_string(mean);  // the mean x was divided by
    out_or_print(c, k, "--curve");
  }
  return 0;
}

int cmd_fit_forms(const Cli& c) {
  std::string label;
  double mean;
  const Vec x = normalised(c, input(c, c.pos[0], "--column", &label), mean);
  std::printf("%s: %zu values divided by their mean %.6g\n", label.c_str(), x.size(), mean);
  const LogNormalFit ln = fit_truncated_lognormal(x);
  const std::vector<std::pair<const char*, Fit>> fits{{"Eq. 7 truncated log-normal", ln.eq7},
                                                      {"truncated normal (Eq. 7's Gaussian limit)", ln.normal},
                                                      {"Eq. 8 q-model", fit_eq8(x)},
                                                      {"Eq. 9", fit_eq9(x)},
                                                      {"Eq. 10 Radjai", fit_eq10(x)}};
  Table t;
  t.meta = {{"source", label}, {"mean", std::to_string(mean)}, {"gaussian_limit", ln.gaussian_limit ? "1" : "0"}};
  for (auto& [title, f] : fits) {
    print_fit(f, title);
    add_params(t, f, f.model + "_");
  }
  std::printf("lowest AIC wins; the Eq. 7 Gaussian limit: %s\n", ln.gaussian_limit ? "yes" : "no");
  out_or_print(c, t);
  if (c.has("--curve")) {
    Histogram h = histogram(x, static_cast<int>(c.count("--nbins", 40)), c.str("--bins", "lin") == "log", false);
    Table k = hist_table(h, label);
    for (auto& [title, f] : fits) {
      Vec y;
      for (double v : h.centres) y.push_back(f.pdf(v));
      k.names.push_back(f.model);
      k.cols.push_back(y);
    }
    out_or_print(c, k, "--curve");
  }
  return 0;
}

int cmd_ks(const Cli& c) {
  std::string la, lb;
  Cli ca = c, cb = c;
  if (c.has("--column-a")) ca.opt["--column"] = c.str("--column-a");
  if (c.has("--column-b")) cb.opt["--column"] = c.str("--column-b");
  const Vec a = input(ca, c.pos[0], "--column", &la), b = input(cb, c.pos[1], "--column", &lb);
  const double alpha = c.num("--alpha", 0.05);
  if (!(alpha > 0 && alpha < 1)) throw Error("--alpha must lie in (0, 1)");
  const Ks k = ks_two_sample(a, b, alpha);
  std::printf("A: %s (%zu values)\nB: %s (%zu values)\n", la.c_str(), a.size(), lb.c_str(), b.size());
  std::printf("KS distance D = %.6g, p-value %.4g, critical D at alpha %.3g: %.6g -> %s\n", k.d, k.p, alpha, k.critical,
              k.d > k.critical ? "different" : "not distinguishable");
  Table t{{"d", "p", "critical", "alpha", "n_a", "n_b"}, {{k.d}, {k.p}, {k.critical}, {alpha}, {double(a.size())}, {double(b.size())}},
          {{"a", la}, {"b", lb}}};
  out_or_print(c, t);
  return 0;
}

int cmd_acf(const Cli& c) {
  std::string label;
  const Vec x = input(c, c.pos[0], "--column", &label);
  const double dt = c.num("--dt", 1), thr = c.num("--threshold", std::exp(-1.0));
  const Vec cc = autocorrelation(x, c.count("--max-lag", std::min<std::size_t>(x.size() / 4, 100000)));
  const double k = first_lag_below(cc, thr);
  const CorrTime t = integrated_time(cc);
  std::printf("%s: %zu values\n", label.c_str(), x.size());
  std::printf("first lag with C < %.4g: %.4g rows = %.6g time units%s\n", thr, k, k * dt, k < 0 ? " (never within --max-lag)" : "");
  std::printf("statistical inefficiency g = 1 + 2 sum C = %.5g (window %zu rows); integrated time g/2 = %.5g rows\n", t.g,
              t.window, t.g / 2);
  Vec lag, time;
  for (std::size_t i = 0; i < cc.size(); ++i) {
    lag.push_back(double(i));
    time.push_back(double(i) * dt);
  }
  Table tab{{"lag", "dt", "c"}, {lag, time, cc},
            {{"source", label}, {"first_lag_below", std::to_string(k)}, {"threshold", std::to_string(thr)},
             {"g", std::to_string(t.g)}}};
  out_or_print(c, tab);
  return 0;
}

int cmd_block_error(const Cli& c) {
  std::string label;
  const Vec x = input(c, c.pos[0], "--column", &label);
  const BlockError e = block_error(x, c.count("--block", 0));
  std::printf("%s: %zu values\n", label.c_str(), x.size());
  std::printf("mean %.10g +- %.4g (block standard error; +- %.2g on the error)\n", e.mean, e.error, e.error_of_error);
  std::printf("blocks: %zu of %zu rows (%s); g = %.5g; uncorrelated formula would say +- %.4g\n", e.nblocks, e.block,
              c.has("--block") ? "given" : "10 g", e.g, e.naive);
  if (e.nblocks < 20) std::printf("WARNING: only %zu blocks: the error is itself uncertain by %.0f %%\n", e.nblocks, 100 * e.error_of_error / e.error);
  Table t{{"mean", "error", "error_of_error", "naive", "g", "block", "nblocks"},
          {{e.mean}, {e.error}, {e.error_of_error}, {e.naive}, {e.g}, {double(e.block)}, {double(e.nblocks)}},
          {{"source", label}}};
  out_or_print(c, t);
  return 0;
}

// Principal stresses from --s1/--s3 or --sxx/--syy[/--sxy], compression positive (--compression-negative flips).
std::vector<Circle> circles_of(const Cli& c, Vec& s1, Vec& s3) {
  const double sign = c.flag("--compression-negative") ? -1 : 1;
  const auto col = [&](const char* k) {
    Cli one = c;
    one.opt["--column"] = c.str(k);
    Vec v = input(one, c.pos[0]);
    for (double& a : v) a *= sign;
    return v;
  };
  if (c.has("--s1") && c.has("--s3")) {
    s1 = col("--s1");
    s3 = col("--s3");
  } else if (c.has("--sxx") && c.has("--syy")) {
    const Vec xx = col("--sxx"), yy = col("--syy"), xy = c.has("--sxy") ? col("--sxy") : Vec(xx.size(), 0.0);
    for (std::size_t i = 0; i < xx.size(); ++i) {
      double a, b;
      principal_2d(xx[i], yy[i], xy[i], a, b);
      s1.push_back(a);
      s3.push_back(b);
    }
  } else {
    throw Error(c.sub + " needs --s1 and --s3, or --sxx, --syy (and --sxy)");
  }
  std::vector<Circle> circ;
  for (std::size_t i = 0; i < s1.size(); ++i) circ.push_back(mohr_circle(s1[i], s3[i]));
  return circ;
}

int cmd_mohr(const Cli& c) {
  const double sign = c.flag("--compression-negative") ? -1 : 1;
  Vec s1, s3, cen, rad;
  const std::vector<Circle> circ = circles_of(c, s1, s3);
  for (auto& k : circ) {
    cen.push_back(k.centre);
    rad.push_back(k.radius);
  }
  const Envelope e = mohr_envelope(circ);
  std::printf("%zu Mohr circles; envelope |tau| = C + mu_M sigma (petit2017 Eq. 8):\n", circ.size());
  std::printf("  mu_M = %.6g +- %.3g   C = %.6g +- %.3g   (cov %.3g; friction angle %.4g deg; rms miss %.3g)\n", e.mu,
              e.mu_err, e.c, e.c_err, e.cov, e.phi * 180 / M_PI, e.rms);
  Table t{{"centre", "radius", "s1", "s3"}, {cen, rad, s1, s3},
          {{"mu_M", std::to_string(e.mu)}, {"mu_M_err", std::to_string(e.mu_err)}, {"C", std::to_string(e.c)},
           {"C_err", std::to_string(e.c_err)}, {"sign", sign < 0 ? "compression was negative, flipped" : "compression positive"}}};
  out_or_print(c, t);
  return 0;
}

int cmd_power_law(const Cli& c) {
  Cli cx = c, cy = c, ce = c;
  cx.opt["--column"] = c.str("--x");
  cy.opt["--column"] = c.str("--y");
  if (!c.has("--x") || !c.has("--y")) throw Error("power-law needs --x and --y columns");
  const Vec x = input(cx, c.pos[0]), y = input(cy, c.pos[0]);
  Vec e;
  if (c.has("--yerr")) {
    ce.opt["--column"] = c.str("--yerr");
    e = input(ce, c.pos[0]);
  }
  const double x0 = c.num("--x0", 1);
  const std::string m = c.str("--method", "nls");
  if (m != "nls" && m != "loglog") throw Error("--method: 'nls' or 'loglog', not '" + m + "'");
  const PowerLaw p = m == "nls" ? power_law_nls(x, y, e, x0) : power_law_loglog(x, y, e, x0);
  std::printf("K = K0 (x / %.6g)^alpha by %s over %zu points:\n  K0 = %.6g +- %.3g   alpha = %.6g +- %.3g   cov %.3g   chi2 %.4g / %zu dof\n",
              x0, p.method.c_str(), x.size(), p.k0, p.k0_err, p.alpha, p.alpha_err, p.cov, p.chi2, p.dof);
  Table t{{"k0", "k0_err", "alpha", "alpha_err", "cov", "x0", "chi2", "dof"},
          {{p.k0}, {p.k0_err}, {p.alpha}, {p.alpha_err}, {p.cov}, {x0}, {p.chi2}, {double(p.dof)}},
          {{"method", p.method}}};
  out_or_print(c, t);
  return 0;
}

// P(phi) of Eq. 9: uniform 1/pi, tabulated (--phi, --p: linear between nodes, 0 outside) or the
// histogram of angle samples (--phi only, --nbins on [-pi/2, pi/2], constant per bin); radians.
struct Density {
  Vec nodes, vals;
  bool steps = false;
  std::string what = "uniform P = 1/pi on [-pi/2, pi/2]";
  double operator()(double phi) const {
    if (nodes.empty()) return 1 / M_PI;
    if (phi < nodes.front() || phi > nodes.back()) return 0.0;
    const std::size_t i = std::min<std::size_t>(gsl_interp_bsearch(nodes.data(), phi, 0, nodes.size() - 1), nodes.size() - 2);
    if (steps) return vals[i];
    const double f = (phi - nodes[i]) / (nodes[i + 1] - nodes[i]);
    return vals[i] + f * (vals[i + 1] - vals[i]);
  }
};

Density eq9_density(const Cli& c, double deg) {
  Density d;
  if (c.pos.empty()) return d;
  Cli cp = c;
  cp.opt["--column"] = c.str("--phi");
  d.nodes = input(cp, c.pos[0]);
  for (double& v : d.nodes) v *= deg;
  if (c.has("--p")) {  // tabulated P(phi)
    cp.opt["--column"] = c.str("--p");
    d.vals = input(cp, c.pos[0]);
    for (double& v : d.vals) v /= deg;  // a density per degree becomes one per radian
    for (std::size_t i = 1; i < d.nodes.size(); ++i)
      if (!(d.nodes[i] > d.nodes[i - 1])) throw Error(c.sub + ": the --phi column must increase");
    d.what = "tabulated P, linear between nodes, 0 outside";
  } else {  // angle samples: their histogram
    const Histogram h = histogram(d.nodes, static_cast<int>(c.count("--nbins", 36)), false, false, -M_PI / 2, M_PI / 2);
    d.what = "histogram of " + std::to_string(d.nodes.size()) + " angles on [-pi/2, pi/2], constant per bin";
    d.nodes = h.edges;
    d.vals = h.pdf;
    d.vals.push_back(h.pdf.back());
    d.steps = true;
  }
  return d;
}

int cmd_quad_eq9(const Cli& c) {
  const double deg = c.flag("--degrees") ? M_PI / 180 : 1.0;
  if (!c.has("--mu") || !c.has("--phi-min")) throw Error("quad-eq9 needs --mu and --phi-min");
  const double mu = c.num("--mu", 0), phi_min = c.num("--phi-min", 0) * deg;
  const Density d = eq9_density(c, deg);
  const std::function<double(double)> p = [&d](double phi) { return d(phi); };
  const Vec& nodes = d.nodes;
  const std::string& what = d.what;
  const Eq9 q = quad_eq9(p, mu, phi_min, nodes);
  std::printf("petit2017 Eq. 9, %s; mu = %.6g, phi_m = %.6g rad, phi in [%.6g, %.6g] rad\n", what.c_str(), mu, std::atan(mu),
              phi_min, q.phi_max);
  std::printf("  <mu_M> = %.8g (P as given; weight of P in the range %.6g)\n  <mu_M> = %.8g (P normalised over the range)\n",
              q.mu_m, q.weight, q.mu_m_window);
  Table t{{"mu_m", "mu_m_window", "weight", "phi_min", "phi_max", "mu", "abserr"},
          {{q.mu_m}, {q.mu_m_window}, {q.weight}, {phi_min}, {q.phi_max}, {mu}, {q.abserr}}, {{"p", what}}};
  out_or_print(c, t);
  return 0;
}

// ---------- the cavity study (kneib2017 Eqs. 4, 5, 16-20) ----------

Vec xy_column(const Cli& c, const char* opt) {
  if (!c.has(opt)) throw Error(c.sub + " needs " + opt + " (a column)");
  Cli one = c;
  one.opt["--column"] = c.str(opt);
  return input(one, c.pos[0]);
}

// --names a,b,...: the parameters' names in the output (e.g. r1,r2,I0 or mu1,mu2,I0).
void rename(const Cli& c, LsqFit& f) {
  if (!c.has("--names")) return;
  std::vector<std::string> n;
  std::string cur;
  for (char ch : c.str("--names") + ",") {
    if (ch != ',') {
      cur += ch;
    } else {
      n.push_back(cur);
      cur.clear();
    }
  }
  if (n.size() != f.params.size()) throw Error("--names wants " + std::to_string(f.params.size()) + " names, comma-separated");
  for (std::size_t i = 0; i < n.size(); ++i) f.params[i].name = n[i];
}

int lsq_report(const Cli& c, LsqFit f, const char* formula) {
  rename(c, f);
  std::printf("%s over %zu points (%s):\n", formula, f.n,
              f.weighted ? "weighted by 1/yerr^2, errors as given" : "unweighted, errors from the scatter (chi2/dof)");
  for (auto& p : f.params)
    std::printf("  %-6s %.6g +- %.3g   95%% [%.6g, %.6g]\n", p.name.c_str(), p.value, p.err, p.lo, p.hi);
  std::printf("  chi2 %.6g / %zu dof   R^2 %.6f   (interval = value -+ %.4g err%s)\n", f.chi2, f.dof, f.r2, f.q,
              f.model == "sigmoid" ? "; x0 in ln x0" : "");
  Table t;
  t.meta = {{"model", formula}, {"errors", f.weighted ? "given (yerr)" : "from the scatter"}};
  for (auto& p : f.params)
    for (auto [suffix, v] : {std::pair{"", p.value}, {"_err", p.err}, {"_lo", p.lo}, {"_hi", p.hi}}) {
      t.names.push_back(p.name + suffix);
      t.cols.push_back({v});
    }
  for (auto [n, v] : {std::pair{"chi2", f.chi2}, {"dof", double(f.dof)}, {"r_squared", f.r2}, {"n", double(f.n)}}) {
    t.names.push_back(n);
    t.cols.push_back({v});
  }
  out_or_print(c, t);
  return 0;
}

int cmd_fit_sigmoid(const Cli& c) {
  const Vec x = xy_column(c, "--x"), y = xy_column(c, "--y"), e = c.has("--yerr") ? xy_column(c, "--yerr") : Vec{};
  const LsqFit f = fit_sigmoid(x, y, e);
  if (c.has("--curve")) {  // the fitted curve on 200 log-spaced points across the data's x
    const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
    Vec cx, cy;
    for (int i = 0; i < 200; ++i) {
      cx.push_back(*lo * std::pow(*hi / *lo, i / 199.0));
      cy.push_back(sigmoid(cx.back(), f.params[0].value, f.params[1].value, f.params[2].value));
    }
    out_or_print(c, Table{{"x", "fit"}, {cx, cy}, {{"model", "a + (b - a)/(1 + x0/x)"}}}, "--curve");
  }
  return lsq_report(c, f, "y = a + (b - a)/(1 + x0/x) (kneib2017 Eq. 4, Eq. 20)");
}

int cmd_fit_linear(const Cli& c) {
  const Vec x = xy_column(c, "--x"), y = xy_column(c, "--y"), e = c.has("--yerr") ? xy_column(c, "--yerr") : Vec{};
  return lsq_report(c, fit_linear_down(x, y, e), "y = c1 - c2 x (kneib2017 Eq. 5)");
}

// ---------- petit2017 (Eqs. 6, 7, 8 per cycle, 9 inverted, 10) ----------

Vec optional_column(const Cli& c, const char* opt) { return c.has(opt) ? xy_column(c, opt) : Vec{}; }

int cmd_bulk_modulus(const Cli& c) {
  const double sign = c.flag("--compression-negative") ? -1 : 1;
  Vec syy = xy_column(c, "--syy"), sxx = xy_column(c, "--sxx"), eyy = xy_column(c, "--eyy");
  for (Vec* v : {&syy, &sxx, &eyy})
    for (double& a : *v) a *= sign;
  const Vec cyc = optional_column(c, "--cycle"), load = optional_column(c, "--loading");
  const std::vector<BulkPoint> k = bulk_modulus(syy, sxx, eyy, cyc, load);
  std::printf("petit2017 Eq. 6, K = (d syy + 2 d sxx) / (3 d eyy) between successive loading states: %zu increments%s\n", k.size(),
              sign < 0 ? " (signs flipped: compression positive)" : "");
  Table t{{"row", "cycle", "syy", "syy_mid", "eyy", "K"}, {}, {{"source", c.pos[0]}, {"K", "petit2017 Eq. 6"},
          {"row", "the increment's end state (1-based row after --skip)"}, {"syy_mid", "mean of the increment's two states"}}};
  t.cols.resize(t.names.size());
  for (auto& b : k) {
    const double row[] = {double(b.row + 1), b.cycle, b.syy, b.syy_mid, b.eyy, b.k};
    for (std::size_t i = 0; i < t.cols.size(); ++i) t.cols[i].push_back(row[i]);
  }
  if (!c.has("--out")) {
    std::printf("%6s %6s %12s %12s %12s %12s\n", "row", "cycle", "syy", "syy_mid", "eyy", "K");
    for (auto& b : k) std::printf("%6zu %6g %12.6g %12.6g %12.6g %12.6g\n", b.row + 1, b.cycle, b.syy, b.syy_mid, b.eyy, b.k);
  }
  out_or_print(c, t);
  return 0;
}

int cmd_fit_offset_power(const Cli& c) {
  const Vec x = xy_column(c, "--x"), y = xy_column(c, "--y"), e = optional_column(c, "--yerr");
  const double s0 = c.has("--sigma0") ? c.num("--sigma0", 0) : *std::min_element(x.begin(), x.end());
  std::printf("sigma0 = %.6g (%s)\n", s0, c.has("--sigma0") ? "given" : "the smallest x");
  const LsqFit f = fit_offset_power(x, y, e, s0);
  if (c.has("--curve")) {
    const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
    Vec cx, cy;
    for (int i = 0; i < 200; ++i) {
      cx.push_back(*lo + (*hi - *lo) * i / 199.0);
      cy.push_back(offset_power(cx.back(), f.params[0].value, f.params[1].value, f.params[2].value, s0));
    }
    out_or_print(c, Table{{"x", "fit"}, {cx, cy}, {{"model", "K0 + a (x/sigma0 - 1)^alpha"}, {"sigma0", std::to_string(s0)}}}, "--curve");
  }
  return lsq_report(c, f, "K = K0 + a (sigma/sigma0 - 1)^alpha (petit2017 Eq. 7)");
}

int cmd_mohr_cycles(const Cli& c) {
  Vec s1, s3;
  const std::vector<Circle> circ = circles_of(c, s1, s3);
  const Vec cyc = xy_column(c, "--cycle"), load = optional_column(c, "--loading");
  const std::vector<CycleEnvelope> ce = cycle_envelopes(circ, cyc, load);
  const double tol = c.num("--tol", 0.005);
  Vec mu;
  for (auto& k : ce) mu.push_back(k.e.mu);
  const long lim = limit_cycle(mu, tol);
  std::printf("envelope |tau| = C + mu_M sigma (petit2017 Eq. 8) of each cycle's %s circles:\n", load.empty() ? "" : "loading");
  std::printf("%8s %5s %10s %9s %10s %9s %8s\n", "cycle", "n", "mu_M", "+-", "C", "+-", "rms");
  Table t{{"cycle", "n", "mu_M", "mu_M_err", "C", "C_err", "rms"}, {}, {{"source", c.pos[0]}, {"tol", std::to_string(tol)}}};
  t.cols.resize(t.names.size());
  for (auto& k : ce) {
    std::printf("%8g %5zu %10.6g %9.3g %10.6g %9.3g %8.3g\n", k.cycle, k.n, k.e.mu, k.e.mu_err, k.e.c, k.e.c_err, k.e.rms);
    const double row[] = {k.cycle, double(k.n), k.e.mu, k.e.mu_err, k.e.c, k.e.c_err, k.e.rms};
    for (std::size_t i = 0; i < t.cols.size(); ++i) t.cols[i].push_back(row[i]);
  }
  if (lim < 0) {
    std::printf("no limit cycle: no cycle before the last has every later mu_M within +-%.3g %% of its own\n", 100 * tol);
  } else {
    std::printf("limit cycle %g: every later mu_M within +-%.3g %% of its mu_M = %.6g +- %.3g\n", ce[lim].cycle, 100 * tol, ce[lim].e.mu,
                ce[lim].e.mu_err);
  }
  char cyc_s[32] = "none", mu_s[32] = "nan";
  if (lim >= 0) {
    std::snprintf(cyc_s, sizeof cyc_s, "%g", ce[lim].cycle);
    std::snprintf(mu_s, sizeof mu_s, "%.17g", ce[lim].e.mu);
  }
  t.meta.push_back({"limit_cycle", cyc_s});
  t.meta.push_back({"limit_mu_M", mu_s});
  out_or_print(c, t);
  return 0;
}

int cmd_phi_min_eq9(const Cli& c) {
  const double deg = c.flag("--degrees") ? M_PI / 180 : 1.0;
  if (!c.has("--mu") || !c.has("--mu-m")) throw Error("phi-min-eq9 needs --mu and --mu-m");
  const double mu = c.num("--mu", 0), mu_m = c.num("--mu-m", 0);
  const Density d = eq9_density(c, deg);
  const bool window = c.flag("--window");
  const auto invert = [&](double m) { return phi_min_eq9([&d](double x) { return d(x); }, mu, m, window, d.nodes); };
  const double phi = invert(mu_m), err = c.num("--mu-m-err", 0);
  std::printf("petit2017 Eq. 9 inverted, %s%s; mu = %.6g, mu_M = %.6g:\n  phi_min = %.8g rad = %.6g deg (phi_max = %.6g deg)\n",
              d.what.c_str(), window ? ", P normalised over the range" : ", P as given", mu, mu_m, phi, phi * 180 / M_PI,
              (std::atan(mu) + M_PI / 4) * 180 / M_PI);
  double lo = phi, hi = phi;  // mu_M -+ err mapped through the inverse (falling in mu_M with P as given)
  if (err > 0) {
    const double a = invert(mu_m + err), b = invert(mu_m - err);
    lo = std::min(a, b);
    hi = std::max(a, b);
    std::printf("  mu_M -+ %.4g gives phi_min in [%.6g, %.6g] deg\n", err, lo * 180 / M_PI, hi * 180 / M_PI);
  }
  Table t{{"phi_min", "phi_min_deg", "phi_min_lo", "phi_min_hi", "mu", "mu_m", "mu_m_err", "window"},
          {{phi}, {phi * 180 / M_PI}, {lo}, {hi}, {mu}, {mu_m}, {err}, {window ? 1.0 : 0.0}}, {{"p", d.what}}};
  out_or_print(c, t);
  return 0;
}

// Angles from --phi (radians, or --degrees), or from branch vectors --dx --dy: phi = atan2(dx, dy), 0 = vertical.
Vec contact_angles(const Cli& c) {
  if (c.has("--phi")) {
    Vec a = xy_column(c, "--phi");
    if (c.flag("--degrees"))
      for (double& v : a) v *= M_PI / 180;
    return a;
  }
  if (!c.has("--dx") || !c.has("--dy")) throw Error("entropy needs --phi, or --dx and --dy");
  const Vec dx = xy_column(c, "--dx"), dy = xy_column(c, "--dy");
  Vec a;
  for (std::size_t i = 0; i < dx.size(); ++i) a.push_back(std::atan2(dx[i], dy[i]));
  return a;
}

int cmd_entropy(const Cli& c) {
  const Vec phi = contact_angles(c), grp = optional_column(c, "--group");
  const int nbins = static_cast<int>(c.count("--nbins", 36));
  std::vector<double> order;
  std::map<double, Vec> by;
  for (std::size_t i = 0; i < phi.size(); ++i) {
    const double g = grp.empty() ? 0 : grp.at(i);
    if (!by.count(g)) order.push_back(g);
    by[g].push_back(phi[i]);
  }
  std::printf("petit2017 Eq. 10, S = -sum P ln P over %d bins of [-pi/2, pi/2] (%.4g deg each; angles folded by pi):\n", nbins,
              180.0 / nbins);
  Table t{{"group", "n", "S"}, {}, {{"source", c.pos[0]}, {"nbins", std::to_string(nbins)}}};
  t.cols.resize(3);
  for (double g : order) {
    const Entropy e = contact_entropy(by[g], nbins);
    char name[64] = "";
    if (!grp.empty()) std::snprintf(name, sizeof name, "group %g: ", g);
    std::printf("  %s%zu angles: S = %.6g (ln nbins = %.6g, a uniform law's)\n", name, by[g].size(), e.s, std::log(double(nbins)));
    for (auto [col, v] : {std::pair{0, g}, {1, double(by[g].size())}, {2, e.s}}) t.cols[col].push_back(v);
  }
  out_or_print(c, t);
  return 0;
}

// A column of a row table; in an HDF5 table of ours every column is its own dataset.
Vec grid_column(const Cli& c, const std::string& name) {
  const std::string& path = c.pos[0];
  Vec v;
  if (is_hdf5_file(path) && !c.has("--dataset") && h5_has_dataset(path, name)) {
    std::vector<std::size_t> dims;
    v = read_h5_array(path, name, dims);
  } else {
    v = read_column(path, name, c.str("--dataset")).values;
  }
  const std::size_t skip = c.count("--skip", 0);
  if (skip >= v.size()) throw Error("--skip " + std::to_string(skip) + " leaves nothing of column " + name);
  return Vec(v.begin() + static_cast<long>(skip), v.end());
}

// fix ave/cg's HDF5 (found by its 'u' and 'shape'), or rows x, y, fields of any table.
Grid2D grid_input(const Cli& c, bool stress) {
  const std::string& path = c.pos[0];
  Grid2D g;
  if (is_hdf5_file(path) && h5_has_dataset(path, "u") && h5_has_dataset(path, "shape")) {
    g = read_cg_grid(path, c.str("--plane", "xy"), stress ? c.str("--stress", "stress_contact") : "", c.count("--skip", 0));
    std::printf("%s: fix ave/cg grid, plane %s, %zu x %zu nodes%s\n", path.c_str(), c.str("--plane", "xy").c_str(), g.nx(), g.ny(),
                stress ? (", stress from '" + c.str("--stress", "stress_contact") + "'").c_str() : "");
  } else {
    const auto name = [&](const char* opt, const char* def) { return c.str(opt, def); };
    const Vec x = grid_column(c, name("--x", "x")), y = grid_column(c, name("--y", "y"));
    Vec vx = grid_column(c, name("--vx", "vx")), vy = grid_column(c, name("--vy", "vy")), sxx, syy, szz, sxy;
    std::vector<std::pair<const Vec*, Vec Grid2D::*>> f{{&vx, &Grid2D::vx}, {&vy, &Grid2D::vy}};
    if (stress) {
      sxx = grid_column(c, name("--sxx", "sxx"));
      syy = grid_column(c, name("--syy", "syy"));
      sxy = grid_column(c, name("--sxy", "sxy"));
      f.insert(f.end(), {{&sxx, &Grid2D::sxx}, {&syy, &Grid2D::syy}, {&sxy, &Grid2D::sxy}});
      try {
        szz = grid_column(c, name("--szz", "szz"));
        f.push_back({&szz, &Grid2D::szz});
      } catch (const Error&) {
        if (c.has("--szz")) throw;
        std::printf("note: no szz column: szz = 0 (a planar assembly, as kneib2017's grains in a plane)\n");
      }
    }
    g = grid_from_rows(x, y, f);
    std::printf("%s: %zu x %zu nodes\n", path.c_str(), g.nx(), g.ny());
  }
  g.xlo = c.num("--xlo", g.xlo);
  g.xhi = c.num("--xhi", g.xhi);
  g.ylo = c.num("--ylo", g.ylo);
  g.yhi = c.num("--yhi", g.yhi);
  if (!(g.xhi > g.xlo) || !(g.yhi > g.ylo)) throw Error("the walls must satisfy xlo < xhi and ylo < yhi");
  std::printf("walls: x in [%.6g, %.6g], y in [%.6g, %.6g]%s\n", g.xlo, g.xhi, g.ylo, g.yhi,
              c.has("--xlo") || c.has("--xhi") || c.has("--ylo") || c.has("--yhi") ? "" : " (the grid's bounds: give --xlo ... for the cavity's)");
  return g;
}

int cmd_vortex_centre(const Cli& c) {
  const std::string wall = c.str("--wall", "right");
  if (wall != "right" && wall != "left") throw Error("--wall: 'right' or 'left', not '" + wall + "'");
  const Grid2D g = grid_input(c, false);
  const Vortex v = vortex_centre(g, wall == "right");
  std::printf("vortex centre (extremum of the stream function%s): x = %.6g, y = %.6g (node %zu, %zu; psi - psi_walls = %.4g)\n",
              v.refined ? ", refined on its 3x3 stencil" : ", NOT refined: the step left the cell", v.x, v.y, v.i + 1, v.j + 1, v.psi);
  std::printf("zero of the bilinear velocity nearby: x = %.6g, y = %.6g\n", v.x_zero, v.y_zero);
  std::printf("l = distance from the %s wall = %.6g; L = %.6g; l/L = %.6f (kneib2017 Sec. III A, Fig. 3(a))\n", wall.c_str(), v.ell,
              g.xhi - g.xlo, v.ell_over_l);
  Table t{{"x", "y", "x_zero", "y_zero", "psi", "refined", "ell", "L", "ell_over_l", "xlo", "xhi"},
          {{v.x}, {v.y}, {v.x_zero}, {v.y_zero}, {v.psi}, {v.refined ? 1.0 : 0.0}, {v.ell}, {g.xhi - g.xlo}, {v.ell_over_l}, {g.xlo}, {g.xhi}},
          {{"source", c.pos[0]}, {"centre", "extremum of psi (vx = dpsi/dy, vy = -dpsi/dx), Newton step on its 3x3 stencil"},
           {"ell", "distance of the centre from the " + wall + " wall"}}};
  out_or_print(c, t);
  if (c.has("--psi")) {
    const Vec psi = stream_function(g);
    Vec x, y;
    for (std::size_t i = 0; i < g.nx(); ++i)
      for (std::size_t j = 0; j < g.ny(); ++j) {
        x.push_back(g.xs[i]);
        y.push_back(g.ys[j]);
      }
    out_or_print(c, Table{{"x", "y", "vx", "vy", "psi"}, {x, y, g.vx, g.vy, psi}, {{"source", c.pos[0]}}}, "--psi");
  }
  return 0;
}

int cmd_local_rheology(const Cli& c) {
  if (!c.has("--d") || !c.has("--rho-p")) throw Error("local-rheology needs --d (grain diameter) and --rho-p (grain density)");
  const std::string reg = c.str("--region", "paper");
  if (reg != "paper" && reg != "all") throw Error("--region: 'paper' or 'all', not '" + reg + "'");
  const Grid2D g = grid_input(c, true);
  const Region r = reg == "paper" ? paper_region(g) : Region{};
  const Rheology rh = local_rheology(g, r, c.num("--d", 0), c.num("--rho-p", 0));
  std::printf("region (%s): nodes %zu-%zu along x, %zu-%zu along y: %zu nodes, %zu without shear or pressure left out\n",
              reg == "paper" ? "kneib2017 Fig. 19: upper half, central L/2" : "the whole grid", rh.i0 + 1, rh.i1 + 1, rh.j0 + 1, rh.j1 + 1,
              rh.nodes, rh.skipped);
  const std::vector<RheologyBin> bins = bin_rheology(rh.points, static_cast<int>(c.count("--nbins", 20)));
  Vec x, y, dxx, dyy, dxy, nd, p, ns, I, ml, mn, al;
  for (auto& q : rh.points)
    for (auto [col, v] : {std::pair{&x, q.x}, {&y, q.y}, {&dxx, q.dxx}, {&dyy, q.dyy}, {&dxy, q.dxy}, {&nd, q.norm_d}, {&p, q.p},
                          {&ns, q.norm_s}, {&I, q.i}, {&ml, q.mu_loc}, {&mn, q.mu_norm}, {&al, q.align}})
      col->push_back(v);
  const std::vector<std::pair<std::string, std::string>> meta{
      {"source", c.pos[0]}, {"d", c.str("--d")}, {"rho_p", c.str("--rho-p")}, {"region", reg},
      {"I", "kneib2017 Eq. 18: d sqrt(rho_p) ||D'|| / sqrt(p), ||A|| = sqrt(Tr(A A^T)/2), A' = A - Tr(A)/3 I_3"},
      {"mu_loc", "Eq. 19 as printed: Tr(sigma' D')/3 / (p ||D'||)"}, {"mu_norm", "||sigma'|| / p"},
      {"align", "Tr(sigma' D') / (2 ||sigma'|| ||D'||)"}};
  out_or_print(c, Table{{"x", "y", "dxx", "dyy", "dxy", "norm_d", "p", "norm_s", "I", "mu_loc", "mu_norm", "align"},
                        {x, y, dxx, dyy, dxy, nd, p, ns, I, ml, mn, al}, meta});
  Table b{{"I_lo", "I_hi", "I", "mu_loc", "mu_loc_se", "mu_norm", "mu_norm_se", "n"}, {}, meta};
  b.cols.resize(b.names.size());
  for (auto& q : bins) {
    const double row[] = {q.i_lo, q.i_hi, q.i_mean, q.mu_loc, q.mu_loc_se, q.mu_norm, q.mu_norm_se, double(q.n)};
    for (std::size_t k = 0; k < b.cols.size(); ++k) b.cols[k].push_back(row[k]);
  }
  if (!c.has("--binned")) {
    std::printf("%12s %10s %10s %10s %6s\n", "I", "mu_loc", "+-", "mu_norm", "n");
    for (auto& q : bins) std::printf("%12.5g %10.5g %10.3g %10.5g %6zu\n", q.i_mean, q.mu_loc, q.mu_loc_se, q.mu_norm, q.n);
  }
  out_or_print(c, b, "--binned");
  if (c.flag("--fit")) {  // Eq. 20 over the nodes, unweighted; a failed fit leaves the outputs written
    LsqFit f;
    try {
      f = fit_sigmoid(I, ml);
    } catch (const Error& e) {
      std::printf("Eq. 20 fit over the nodes failed: %s\n", e.what());
      return 1;
    }
    f.params[0].name = "mu1";
    f.params[1].name = "mu2";
    f.params[2].name = "I0";
    std::printf("Eq. 20 on mu_loc over the %zu nodes:", I.size());
    for (auto& q : f.params) std::printf("  %s = %.5g +- %.3g", q.name.c_str(), q.value, q.err);
    std::printf("  (R^2 %.4f)\n", f.r2);
  }
  return 0;
}

const std::vector<Sub>& subs() {
  static const std::vector<Sub> s{
      {"pdf", "pdf IN --column C [--bins lin|log] [--nbins 50] [--lo X --hi X] [--raw] [--out F.csv|F.h5]",
       "Histogram and PDF of a column, values divided by their mean unless --raw (--lo, --hi in those units;\n"
       "default: the data's range); log bins drop x <= 0.",
       {"--column", "--dataset", "--skip", "--bins", "--nbins", "--lo", "--hi", "--out"}, {"--raw"}, 1, 1, cmd_pdf},
      {"fit-lognormal", "fit-lognormal IN --column C [--raw] [--out params.csv] [--curve curve.csv [--nbins 40] [--bins lin|log]]",
       "Maximum-likelihood fit of kneib2017 Eq. 7 (truncated log-normal) with profile-likelihood 95 % intervals,\n"
       "KS goodness of fit, and the Gaussian-limit test against the truncated normal.",
       {"--column", "--dataset", "--skip", "--out", "--curve", "--nbins", "--bins"}, {"--raw"}, 1, 1, cmd_fit_lognormal},
      {"fit-forms", "fit-forms IN --column C [--raw] [--out params.csv] [--curve curve.csv]",
       "Fits Eq. 7, its Gaussian limit and the alternative forms Eqs. 8-10 of kneib2017; compares loglik, AIC, KS.",
       {"--column", "--dataset", "--skip", "--out", "--curve", "--nbins", "--bins"}, {"--raw"}, 1, 1, cmd_fit_forms},
      {"ks", "ks A B [--column C | --column-a C --column-b C] [--alpha 0.05] [--out F]",
       "Two-sample Kolmogorov-Smirnov distance, p-value and critical distance.",
       {"--column", "--column-a", "--column-b", "--dataset", "--skip", "--alpha", "--out"}, {}, 2, 2, cmd_ks},
      {"acf", "acf IN --column C [--max-lag L] [--threshold 0.3679] [--dt DT] [--out F]",
       "Autocorrelation C(k) (FFT), first lag under the threshold (interpolated in ln C), statistical inefficiency.",
       {"--column", "--dataset", "--skip", "--max-lag", "--threshold", "--dt", "--out"}, {}, 1, 1, cmd_acf},
      {"block-error", "block-error IN --column C [--block B] [--out F]",
       "Standard error of the mean of a correlated series by block averages; blocks of 10 g rows unless --block.",
       {"--column", "--dataset", "--skip", "--block", "--out"}, {}, 1, 1, cmd_block_error},
      {"mohr-envelope", "mohr-envelope IN (--s1 C --s3 C | --sxx C --syy C [--sxy C]) [--compression-negative] [--out F]",
       "Mohr circles from principal (or 2D) stresses and the least-squares tangent line |tau| = C + mu_M sigma.",
       {"--s1", "--s3", "--sxx", "--syy", "--sxy", "--dataset", "--skip", "--out"}, {"--compression-negative"}, 1, 1, cmd_mohr},
      {"power-law", "power-law IN --x C --y C [--yerr C] [--x0 X] [--method nls|loglog] [--out F]",
       "Fit K = K0 (x/x0)^alpha: GSL nonlinear least squares (default) or a (weighted) log-log line, with covariance.",
       {"--x", "--y", "--yerr", "--x0", "--method", "--dataset", "--skip", "--out"}, {}, 1, 1, cmd_power_law},
      {"quad-eq9", "quad-eq9 --mu M --phi-min P [--degrees] [IN --phi C [--p C | --nbins 36]] [--out F]",
       "petit2017 Eq. 9 by GSL quadrature: P uniform, tabulated (--phi, --p) or the histogram of angle samples (--phi).",
       {"--mu", "--phi-min", "--phi", "--p", "--nbins", "--dataset", "--skip", "--out"}, {"--degrees"}, 0, 1, cmd_quad_eq9},
      {"bulk-modulus", "bulk-modulus IN --syy C --sxx C --eyy C [--cycle C] [--loading C] [--compression-negative] [--out F]",
       "petit2017 Eq. 6 between successive states of each loading branch: K = (d syy + 2 d sxx) / (3 d eyy), compression\n"
       "positive (eyy = dH/H, Eq. 4). A branch: consecutive rows of one --cycle with --loading != 0 (without them: all rows).\n"
       "Per increment: its end row, cycle, syy, the mean syy of its two states, eyy, K.",
       {"--syy", "--sxx", "--eyy", "--cycle", "--loading", "--dataset", "--skip", "--out"}, {"--compression-negative"}, 1, 1,
       cmd_bulk_modulus},
      {"fit-offset-power", "fit-offset-power IN --x C --y C [--yerr C] [--sigma0 S] [--out F] [--curve F]",
       "petit2017 Eq. 7 with its offset, K = K0 + a (sigma/sigma0 - 1)^alpha (sigma0 fixed: given, or the smallest x), by\n"
       "GSL nonlinear least squares started from a scan in alpha; standard errors (scaled by chi2/dof without --yerr),\n"
       "95 % intervals, chi2, R^2. The paper's a = 0.29 MPa is not compared (see README).",
       {"--x", "--y", "--yerr", "--sigma0", "--dataset", "--skip", "--out", "--curve"}, {}, 1, 1, cmd_fit_offset_power},
      {"mohr-cycles", "mohr-cycles IN (--s1 C --s3 C | --sxx C --syy C [--sxy C]) --cycle C [--loading C] [--tol 0.005]\n"
       "                    [--compression-negative] [--out F]",
       "The Mohr envelope (petit2017 Eq. 8, as mohr-envelope) of each cycle's loading circles, mu_M and C per cycle, and\n"
       "the limit cycle: the first cycle whose mu_M every later cycle matches within +-tol (relative; default 0.5 %).",
       {"--s1", "--s3", "--sxx", "--syy", "--sxy", "--cycle", "--loading", "--tol", "--dataset", "--skip", "--out"},
       {"--compression-negative"}, 1, 1, cmd_mohr_cycles},
      {"phi-min-eq9", "phi-min-eq9 --mu M --mu-m X [--mu-m-err E] [--window] [--degrees] [IN --phi C [--p C | --nbins 36]] [--out F]",
       "petit2017 Eq. 9 inverted: the phi_min at which Eq. 9 gives mu_M (Brent's method on quad-eq9; P as quad-eq9's;\n"
       "--window: P normalised over [phi_min, phi_max]); --mu-m-err: the phi_min range of mu_M -+ E.",
       {"--mu", "--mu-m", "--mu-m-err", "--phi", "--p", "--nbins", "--dataset", "--skip", "--out"}, {"--degrees", "--window"}, 0, 1, cmd_phi_min_eq9},
      {"entropy", "entropy IN (--phi C [--degrees] | --dx C --dy C) [--group C] [--nbins 36] [--out F]",
       "petit2017 Eq. 10: contact-angle entropy S = -sum P ln P over --nbins bins of [-pi/2, pi/2], angles from the\n"
       "vertical (from branch vectors: atan2(dx, dy)), folded by pi; one S per --group value (e.g. a state column).",
       {"--phi", "--dx", "--dy", "--group", "--nbins", "--dataset", "--skip", "--out"}, {"--degrees"}, 1, 1, cmd_entropy},
      {"fit-sigmoid", "fit-sigmoid IN --x C --y C [--yerr C] [--names a,b,x0] [--out F] [--curve F]",
       "Weighted nonlinear least squares of y = a + (b - a)/(1 + x0/x), x0 > 0 (kneib2017 Eq. 4: r1, r2, I_M^0;\n"
       "Eq. 20: mu1, mu2, I0), fitted in (a, b, ln x0): standard errors from the covariance (scaled by chi2/dof\n"
       "without --yerr), 95 % intervals (x0's in ln x0), chi2, R^2. --curve: the fit on 200 log-spaced x.",
       {"--x", "--y", "--yerr", "--names", "--dataset", "--skip", "--out", "--curve"}, {}, 1, 1, cmd_fit_sigmoid},
      {"fit-linear", "fit-linear IN --x C --y C [--yerr C] [--names c1,c2] [--out F]",
       "Least-squares line y = c1 - c2 x (kneib2017 Eq. 5: F/(PLd) on l/L) with standard errors, 95 % intervals, R^2.",
       {"--x", "--y", "--yerr", "--names", "--dataset", "--skip", "--out"}, {}, 1, 1, cmd_fit_linear},
      {"vortex-centre", "vortex-centre IN [--plane xy|xz|yz] [--x C --y C --vx C --vy C] [--xlo X --xhi X] [--wall right|left]\n"
       "                    [--skip N] [--out F] [--psi F]",
       "The vortex centre of a mean velocity field on a regular grid: the extremum of the stream function\n"
       "(vx = dpsi/dy, vy = -dpsi/dx, trapezoid rule from a corner), refined by a Newton step on its 3x3 stencil;\n"
       "the zero of the bilinear velocity nearby as a cross-check; l = its distance from the right wall (the one\n"
       "the lid moves towards) and l/L (kneib2017 Sec. III A). IN: fix ave/cg's HDF5 (mean over the windows after\n"
       "--skip N; --plane picks the axes along and up, the third is averaged over) or a table with one row per\n"
       "node (columns x, y, vx, vy by default; repeated nodes averaged). Walls default to the grid's bounds.",
       {"--plane", "--x", "--y", "--vx", "--vy", "--xlo", "--xhi", "--ylo", "--yhi", "--wall", "--dataset", "--skip", "--out", "--psi"},
       {}, 1, 1, cmd_vortex_centre},
      {"local-rheology", "local-rheology IN --d D --rho-p R [--region paper|all] [--stress stress_contact] [--plane xy]\n"
       "                    [--x --y --vx --vy --sxx --syy --szz --sxy C] [--xlo --xhi --ylo --yhi X] [--nbins 20]\n"
       "                    [--out points.csv] [--binned bins.csv] [--fit]",
       "Local inertial number and friction from mean velocity and stress grids (kneib2017 Eqs. 16-19): D = sym grad v\n"
       "by finite differences over the region's nodes only, I = d sqrt(rho_p) ||D'|| / sqrt(p), mu_loc =\n"
       "Tr(sigma' D')/3 / (p ||D'||), also ||sigma'||/p and the alignment of sigma' with D'; stress compression\n"
       "positive (fix ave/cg's). Region 'paper' (Fig. 19): the upper half between the walls in y, the central L/2\n"
       "in x. Per-node rows (--out) and means in log bins of I (--binned); --fit: Eq. 20 over the nodes. Inputs as\n"
       "vortex-centre; a table without szz is taken as planar (szz = 0).",
       {"--d", "--rho-p", "--region", "--stress", "--plane", "--x", "--y", "--vx", "--vy", "--sxx", "--syy", "--szz", "--sxy", "--xlo",
        "--xhi", "--ylo", "--yhi", "--nbins", "--dataset", "--skip", "--out", "--binned"},
       {"--fit"}, 1, 1, cmd_local_rheology},
  };
  return s;
}

void usage_all() {
  std::printf("usage: sable-analyze SUBCOMMAND ... (sable-analyze SUBCOMMAND --help)\n\n");
  for (auto& s : subs()) std::printf("  %s\n", s.usage);
  std::printf("\nOutputs ending in .h5 are HDF5 (one dataset per column), anything else CSV.\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    usage_all();
    return argc < 2 ? 1 : 0;
  }
  const auto it = std::find_if(subs().begin(), subs().end(), [&](const Sub& s) { return s.name == std::string(argv[1]); });
  if (it == subs().end()) {
    std::fprintf(stderr, "sable-analyze: unknown subcommand '%s'\n", argv[1]);
    usage_all();
    return 1;
  }
  const Sub& sub = *it;
  try {
    Cli c;
    c.sub = sub.name;
    for (int i = 2; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--help" || a == "-h") {
        std::printf("usage: sable-analyze %s\n\n%s\n\n%s", sub.usage, sub.help, kReadOpts);
        return 0;
      }
      if (a.rfind("--", 0) == 0) {
        if (std::find(sub.switches.begin(), sub.switches.end(), a) != sub.switches.end()) {
          c.flags.insert(a);
        } else if (std::find(sub.valued.begin(), sub.valued.end(), a) != sub.valued.end()) {
          if (i + 1 >= argc) throw Error(a + " needs a value");
          c.opt[a] = argv[++i];
        } else {
          throw Error("unknown option " + a + " (see sable-analyze " + sub.name + " --help)");
        }
      } else {
        c.pos.push_back(a);
      }
    }
    if (c.pos.size() < sub.min_pos || c.pos.size() > sub.max_pos)
      throw Error("expected " + std::to_string(sub.min_pos) + (sub.min_pos == sub.max_pos ? "" : "-" + std::to_string(sub.max_pos)) +
                  " input file(s), got " + std::to_string(c.pos.size()) + "\nusage: sable-analyze " + sub.usage);
    return sub.run(c);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sable-analyze %s: error: %s\n", sub.name, e.what());
    return 1;
  }
}
