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

int cmd_mohr(const Cli& c) {
  const double sign = c.flag("--compression-negative") ? -1 : 1;
  Vec s1, s3;
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
    throw Error("mohr-envelope needs --s1 and --s3, or --sxx, --syy (and --sxy)");
  }
  std::vector<Circle> circ;
  Vec cen, rad;
  for (std::size_t i = 0; i < s1.size(); ++i) {
    circ.push_back(mohr_circle(s1[i], s3[i]));
    cen.push_back(circ.back().centre);
    rad.push_back(circ.back().radius);
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

int cmd_quad_eq9(const Cli& c) {
  const double deg = c.flag("--degrees") ? M_PI / 180 : 1.0;
  if (!c.has("--mu") || !c.has("--phi-min")) throw Error("quad-eq9 needs --mu and --phi-min");
  const double mu = c.num("--mu", 0), phi_min = c.num("--phi-min", 0) * deg;
  std::function<double(double)> p = [](double) { return 1 / M_PI; };
  std::string what = "uniform P = 1/pi on [-pi/2, pi/2]";
  Vec nodes, vals;
  if (!c.pos.empty()) {
    Cli cp = c;
    if (c.has("--p")) {  // tabulated P(phi)
      cp.opt["--column"] = c.str("--phi");
      nodes = input(cp, c.pos[0]);
      cp.opt["--column"] = c.str("--p");
      vals = input(cp, c.pos[0]);
      for (double& v : nodes) v *= deg;
      for (double& v : vals) v /= deg;  // a density per degree becomes one per radian
      for (std::size_t i = 1; i < nodes.size(); ++i)
        if (!(nodes[i] > nodes[i - 1])) throw Error("quad-eq9: the --phi column must increase");
      what = "tabulated P, linear between nodes, 0 outside";
    } else {  // angle samples: their histogram
      cp.opt["--column"] = c.str("--phi");
      Vec a = input(cp, c.pos[0]);
      for (double& v : a) v *= deg;
      Histogram h = histogram(a, static_cast<int>(c.count("--nbins", 36)), false, false, -M_PI / 2, M_PI / 2);
      nodes = h.edges;
      vals = h.pdf;
      vals.push_back(h.pdf.back());
      what = "histogram of " + std::to_string(a.size()) + " angles on [-pi/2, pi/2], constant per bin";
    }
  }
  const bool steps = !c.has("--p") && !nodes.empty();
  if (!nodes.empty())
    p = [&](double phi) {
      if (phi < nodes.front() || phi > nodes.back()) return 0.0;
      const std::size_t i = std::min<std::size_t>(gsl_interp_bsearch(nodes.data(), phi, 0, nodes.size() - 1), nodes.size() - 2);
      if (steps) return vals[i];
      const double f = (phi - nodes[i]) / (nodes[i + 1] - nodes[i]);
      return vals[i] + f * (vals[i + 1] - vals[i]);
    };
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
