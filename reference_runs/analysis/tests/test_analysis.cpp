// The analysis library recovers known answers (issue 23, "How it is shown").
// Samples come from GSL's mt19937 with fixed seeds, so every run sees the same numbers.
#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <unistd.h>

#include "reference_runs/analysis/analysis.h"
#include "reference_runs/analysis/tests/gsl_rng.h"

using namespace sable::analysis;

namespace {

Vec truncated_lognormal(gsl_rng* r, std::size_t n, double mu, double sigma, double x0) {
  Vec x;
  while (x.size() < n) {
    const double y = gsl_ran_lognormal(r, mu, sigma);
    if (y > x0) x.push_back(y - x0);  // Eq. 7: the law of y - x0 given y > x0
  }
  return x;
}

Vec ar1(gsl_rng* r, std::size_t n, double phi) {  // x_t = phi x_{t-1} + e_t, e ~ N(0, 1), stationary start
  Vec x(n);
  x[0] = gsl_ran_gaussian_ziggurat(r, 1.0 / std::sqrt(1 - phi * phi));
  for (std::size_t t = 1; t < n; ++t) x[t] = phi * x[t - 1] + gsl_ran_gaussian_ziggurat(r, 1.0);
  return x;
}

// The truth lies within 1.5 times the 95 % profile interval's half-width on its side of
// the estimate (about 3 standard errors), and the interval is closed.
void expect_recovered(const Param& p, double truth) {
  SCOPED_TRACE(p.name);
  ASSERT_FALSE(p.ci.lo_open || p.ci.hi_open) << p.ci.lo << " " << p.ci.hi;
  EXPECT_LT(p.ci.lo, p.value);
  EXPECT_GT(p.ci.hi, p.value);
  const double half = truth < p.value ? p.value - p.ci.lo : p.ci.hi - p.value;
  EXPECT_LT(std::fabs(truth - p.value), 1.5 * half) << "estimate " << p.value << " [" << p.ci.lo << ", " << p.ci.hi << "]";
}

}  // namespace

TEST(AnalysisLogNormal, RecoversEq7ParametersWithinProfileIntervals) {
  // Shape like kneib2017 Fig. 12(b) at intermediate I_M: clearly non-Gaussian.
  Rng r(1);
  const double mu = 0.2, sigma = 0.5, x0 = 0.6;
  const Vec x = truncated_lognormal(r, 4000, mu, sigma, x0);
  const LogNormalFit f = fit_truncated_lognormal(x);
  EXPECT_FALSE(f.gaussian_limit);
  ASSERT_EQ(f.eq7.params.size(), 3u);
  expect_recovered(f.eq7.params[0], mu);
  expect_recovered(f.eq7.params[1], sigma);
  expect_recovered(f.eq7.params[2], x0);
  // The intervals are informative: sigma to better than +-30 % at n = 4000.
  EXPECT_LT(f.eq7.params[1].ci.hi - f.eq7.params[1].ci.lo, 0.3);
  // Goodness of fit against the fitted CDF: KS distance well under the 5 % critical value.
  EXPECT_LT(f.eq7.ks.d, f.eq7.ks.critical);
  // The log-likelihood beats the truncated normal's by far (LR >> 1.92).
  EXPECT_GT(f.eq7.loglik - f.normal.loglik, 50);
}

TEST(AnalysisLogNormal, GaussianSamplesAreFlaggedAsTheGaussianLimit) {
  // N(1, 0.15): P(x <= 0) = 1e-11, so the truncation is immaterial; Eq. 7 can only
  // approach it by x0 -> inf, sigma -> 0 and must gain less than 1.92 in log-likelihood.
  Rng r(2);
  Vec x;
  for (int i = 0; i < 3000; ++i) x.push_back(1 + gsl_ran_gaussian(r, 0.15));
  const LogNormalFit f = fit_truncated_lognormal(x);
  EXPECT_TRUE(f.gaussian_limit) << "LR gain " << f.eq7.loglik - f.normal.loglik << " x0 " << f.eq7.params[2].value;
  ASSERT_EQ(f.normal.params.size(), 2u);
  expect_recovered(f.normal.params[0], 1.0);
  expect_recovered(f.normal.params[1], 0.15);
  EXPECT_LT(f.normal.ks.d, f.normal.ks.critical);
}

TEST(AnalysisForms, Eq8GammaShapeRecovered) {
  Rng r(3);
  const double k = 3;  // q-model, unit mean: Gamma(k, 1/k)
  Vec x;
  for (int i = 0; i < 3000; ++i) x.push_back(gsl_ran_gamma(r, k, 1 / k));
  const Fit f = fit_eq8(x);
  expect_recovered(f.params[0], k);
  EXPECT_LT(f.ks.d, f.ks.critical);
}

TEST(AnalysisForms, Eq9ParametersRecovered) {
  // Rejection from the exponential: accept with probability 1 - b exp(-x^2) (b in [0, 1]).
  Rng r(4);
  const double b = 0.6, beta = 1.5;
  Vec x;
  while (x.size() < 4000) {
    const double v = gsl_ran_exponential(r, 1 / beta);
    if (gsl_rng_uniform(r) < 1 - b * std::exp(-v * v)) x.push_back(v);
  }
  const Fit f = fit_eq9(x);
  ASSERT_EQ(f.params.size(), 3u);  // a (from the normalisation), b, beta
  expect_recovered(f.params[1], b);
  expect_recovered(f.params[2], beta);
  EXPECT_LT(f.ks.d, f.ks.critical);
}

TEST(AnalysisForms, Eq10GammaRecovered) {
  // Inverse CDF of Eq. 10: F = 1 - (1 + g)/(1 + g e^{beta x}).
  Rng r(5);
  const double g = 0.5, beta = (1 + g) * std::log1p(1 / g);
  Vec x;
  for (int i = 0; i < 4000; ++i) {
    const double u = gsl_rng_uniform(r);
    x.push_back(std::log(((1 + g) / (1 - u) - 1) / g) / beta);
  }
  const Fit f = fit_eq10(x);
  expect_recovered(f.params[0], g);
  EXPECT_NEAR(f.params[1].value, (1 + f.params[0].value) * std::log1p(1 / f.params[0].value), 1e-12);
  EXPECT_LT(f.ks.d, f.ks.critical);
}

TEST(AnalysisKs, SameLawUnderCriticalDifferentLawsOver) {
  Rng r(6);
  Vec a, b, c;
  for (int i = 0; i < 2000; ++i) {
    a.push_back(gsl_ran_gaussian(r, 1));
    b.push_back(gsl_ran_gaussian(r, 1));
    c.push_back(0.2 + gsl_ran_gaussian(r, 1));  // shift 0.2 sd: expected D ~ 0.08 > D_crit ~ 0.043
  }
  const Ks same = ks_two_sample(a, b), diff = ks_two_sample(a, c);
  EXPECT_LT(same.d, same.critical);
  EXPECT_GT(same.p, 0.05);
  EXPECT_GT(diff.d, diff.critical);
  EXPECT_LT(diff.p, 0.05);
  // 1.358 = c(0.05), the Kolmogorov distribution's 95 % quantile (Smirnov's table): Q = 0.05.
  EXPECT_NEAR(kolmogorov_q(1.3581), 0.05, 2e-4);
  EXPECT_NEAR(same.critical, 1.3581 / std::sqrt(1000.0), 1e-4);  // n_eff = 2000 * 2000 / 4000
}

TEST(AnalysisCorrelation, Ar1AutocorrelationTime) {
  // C(k) = phi^k: the 1/e crossing is at -1/ln(phi) = 9.49 exactly; the statistical
  // inefficiency 1 + 2 sum C = (1 + phi)/(1 - phi) = 19. Sampling error of C near 1/e
  // at N = 1e6 is ~0.003, i.e. ~0.1 lag: 3 % covers > 3 sigma.
  Rng r(7);
  const double phi = 0.9;
  const Vec x = ar1(r, 1000000, phi);
  const Vec c = autocorrelation(x, 200);
  EXPECT_NEAR(c[1], phi, 0.005);
  EXPECT_NEAR(first_lag_below(c, std::exp(-1.0)), -1 / std::log(phi), 0.03 * 9.49);
  const CorrTime t = integrated_time(c);
  EXPECT_NEAR(t.g, (1 + phi) / (1 - phi), 0.05 * 19);
  EXPECT_GE(double(t.window), 3 * t.g);
}

TEST(AnalysisCorrelation, Ar1BlockErrorOfTheMean) {
  // Exact: Var(mean) = sigma_x^2 / N (1 + phi)/(1 - phi), sigma_x^2 = 1/(1 - phi^2).
  // Blocks of b = 10 g underestimate it by 2 phi / (b (1 - phi)(1 + phi)) = 5 % (b = 190);
  // the estimate's own error is error_of_error (~1.5 %): tolerance 5 % + 3 of those.
  Rng r(8);
  const double phi = 0.9;
  const std::size_t n = 1000000;
  const Vec x = ar1(r, n, phi);
  const BlockError e = block_error(x);
  const double exact = std::sqrt(1 / (1 - phi * phi) / double(n) * (1 + phi) / (1 - phi));
  EXPECT_NEAR(e.error, exact, exact * 0.05 + 3 * e.error_of_error);
  EXPECT_NEAR(e.naive * std::sqrt(19.0), exact, 0.05 * exact);  // the uncorrelated formula is sqrt(g) too small
  EXPECT_GE(e.block, 180u);
  EXPECT_NEAR(e.mean, 0, 5 * exact);
}

TEST(AnalysisMohr, EnvelopeOfConstructedCircles) {
  // Circles built tangent to |tau| = C + mu sigma: r = (C + mu c)/sqrt(1 + mu^2).
  const double mu = 0.5, c0 = 0.1;
  std::vector<Circle> exact, noisy;
  Rng r(9);
  for (int i = 1; i <= 10; ++i) {
    const double c = i, rad = (c0 + mu * c) / std::sqrt(1 + mu * mu);
    exact.push_back(mohr_circle(c + rad, c - rad));
    noisy.push_back({c, rad * (1 + gsl_ran_gaussian(r, 0.01))});
  }
  const Envelope e = mohr_envelope(exact);
  EXPECT_NEAR(e.mu, mu, 1e-12);
  EXPECT_NEAR(e.c, c0, 1e-12);
  EXPECT_NEAR(e.rms, 0, 1e-12);
  const Envelope n = mohr_envelope(noisy);  // 1 % radius noise: within 3 stated errors
  EXPECT_NEAR(n.mu, mu, 3 * n.mu_err);
  EXPECT_NEAR(n.c, c0, 3 * n.c_err);
  EXPECT_GT(n.mu_err, 0);
  double s1, s3;  // principal stresses of a 2D tensor: eigenvalues of [[3, 1], [1, 1]] = 2 +- sqrt(2)
  principal_2d(3, 1, 1, s1, s3);
  EXPECT_NEAR(s1, 2 + std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(s3, 2 - std::sqrt(2.0), 1e-14);
}

TEST(AnalysisPowerLaw, KnownExponentRecovered) {
  // petit2017 Fig. 2 magnitudes: K = 200 (sigma / 4.1)^0.47, 3 % multiplicative noise.
  Rng r(10);
  Vec x, y, e;
  for (int i = 0; i < 25; ++i) {
    const double s = 4.1 * std::pow(10.0, i / 12.0);
    x.push_back(s);
    y.push_back(200 * std::pow(s / 4.1, 0.47) * (1 + gsl_ran_gaussian(r, 0.03)));
    e.push_back(0.03 * y.back());
  }
  for (const PowerLaw& p : {power_law_loglog(x, y, e, 4.1), power_law_nls(x, y, e, 4.1), power_law_loglog(x, y, {}, 4.1)}) {
    SCOPED_TRACE(p.method);
    EXPECT_NEAR(p.alpha, 0.47, 3 * p.alpha_err);
    EXPECT_NEAR(p.k0, 200, 3 * p.k0_err);
    EXPECT_LT(p.alpha_err, 0.02);  // the fit is informative
  }
  // Exact data: exact answer.
  Vec ye;
  for (double s : x) ye.push_back(200 * std::pow(s / 4.1, 0.47));
  EXPECT_NEAR(power_law_nls(x, ye, {}, 4.1).alpha, 0.47, 1e-9);
}

TEST(AnalysisQuadrature, PetitEq9UniformDistribution) {
  // P = 1/pi on [-pi/2, pi/2]: integral of tan(2/3 (phi_max - phi)) from phi_min to phi_max
  // is -(3/2) ln cos(2/3 (phi_max - phi_min)).
  const double mu = 0.3, phi_min = -M_PI / 6;
  const Eq9 q = quad_eq9([](double) { return 1 / M_PI; }, mu, phi_min);
  const double phi_max = std::atan(mu) + M_PI / 4;
  const double exact = -1.5 * std::log(std::cos(2.0 / 3.0 * (phi_max - phi_min))) / M_PI;
  EXPECT_NEAR(q.mu_m, exact, 1e-10);
  EXPECT_NEAR(q.weight, (phi_max - phi_min) / M_PI, 1e-12);
  EXPECT_NEAR(q.mu_m_window, exact / q.weight, 1e-10);
}

TEST(AnalysisHistogram, NormalisedByMeanLinearAndLog) {
  Rng r(11);
  Vec x;
  for (int i = 0; i < 10000; ++i) x.push_back(gsl_ran_exponential(r, 2.0));
  const Histogram h = histogram(x, 40, false, true);
  double integral = 0;
  for (std::size_t i = 0; i < h.pdf.size(); ++i) integral += h.pdf[i] * (h.edges[i + 1] - h.edges[i]);
  EXPECT_NEAR(integral, 1, 1e-12);  // every value inside the default range
  EXPECT_NEAR(h.mean, 2, 0.1);
  // Exp(1) after normalising: pdf(x) = e^-x; first bin's centre value within 5 %.
  EXPECT_NEAR(h.pdf[0], std::exp(-h.centres[0]), 0.05);
  const Histogram l = histogram(x, 20, true, true, 1e-3, 10);
  EXPECT_NEAR(l.edges[1] / l.edges[0], std::pow(1e4, 1 / 20.0), 1e-12);  // geometric edges
  EXPECT_NEAR(l.centres[5], std::sqrt(l.edges[5] * l.edges[6]), 1e-15);
}

TEST(AnalysisFiles, ReadsTextDumpAndHdf5AndNamesBadColumns) {
  const auto dir = std::filesystem::temp_directory_path() / ("sable_analysis_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string txt = (dir / "ave.txt").string(), dump = (dir / "d.dump").string(), h5 = (dir / "t.h5").string();
  std::ofstream(txt) << "# Time-averaged data for fix f\n# TimeStep c_a v_b\n0 1.5 2\n10 2.5 3\n";
  std::ofstream(dump) << "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\n"
                         "ITEM: ATOMS id radius\n1 0.5 \n2 0.25 \nITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n1\n"
                         "ITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\nITEM: ATOMS id radius\n1 0.75 \n";
  EXPECT_EQ(read_column(txt, "v_b").values, (Vec{2, 3}));
  EXPECT_EQ(read_column(txt, "2").values, (Vec{1.5, 2.5}));
  EXPECT_EQ(read_column(dump, "radius").values, (Vec{0.5, 0.25, 0.75}));
  write_table(h5, {{"x", "y"}, {{1, 2}, {3, 4}}, {{"what", "test"}}});
  EXPECT_EQ(read_column(h5, "", "y").values, (Vec{3, 4}));
  try {
    read_column(txt, "c_zz");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ave.txt"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("c_zz"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_column(txt, "9"), Error);
  EXPECT_THROW(read_column(h5, "", "nope"), Error);
  std::filesystem::remove_all(dir);
}
