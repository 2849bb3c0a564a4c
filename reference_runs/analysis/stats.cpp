// Histograms, Kolmogorov-Smirnov, autocorrelation and block errors.
#include <gsl/gsl_fft_complex.h>

#include <algorithm>
#include <cmath>

#include "reference_runs/analysis/analysis.h"

namespace sable::analysis {

double mean_of(const Vec& x) {
  if (x.empty()) throw Error("no values");
  double s = 0;
  for (double v : x) s += v;
  return s / static_cast<double>(x.size());
}

Histogram histogram(const Vec& x, int nbins, bool log_bins, bool by_mean, double lo, double hi) {
  if (nbins < 1) throw Error("--nbins must be at least 1");
  Histogram h;
  h.mean = by_mean ? mean_of(x) : 1.0;
  if (by_mean && !(h.mean > 0)) throw Error("cannot normalise by the mean: it is " + std::to_string(h.mean));
  Vec y;
  for (double v : x)
    if (!log_bins || v > 0) y.push_back(v / h.mean);
  if (y.empty()) throw Error("no positive values for log bins");
  if (!(hi > lo)) {  // default range: the data's
    lo = *std::min_element(y.begin(), y.end());
    hi = *std::max_element(y.begin(), y.end());
    if (hi == lo) hi = lo + 1;
  }
  if (log_bins && !(lo > 0)) throw Error("log bins need a positive lower edge");
  for (int i = 0; i <= nbins; ++i) {
    const double f = double(i) / nbins;
    h.edges.push_back(log_bins ? lo * std::pow(hi / lo, f) : lo + (hi - lo) * f);
  }
  h.edges.back() = hi;  // the maximum falls in the last bin
  h.counts.assign(nbins, 0.0);
  for (double v : y) {
    if (v < lo || v > hi) continue;
    const auto it = std::upper_bound(h.edges.begin(), h.edges.end(), v);
    const long k = std::min<long>(std::distance(h.edges.begin(), it) - 1, nbins - 1);
    h.counts[k] += 1;
  }
  double inside = 0;
  for (double c : h.counts) inside += c;
  h.n = x.size();
  h.outside = x.size() - static_cast<std::size_t>(inside);
  for (int i = 0; i < nbins; ++i) {
    const double a = h.edges[i], b = h.edges[i + 1];
    h.centres.push_back(log_bins ? std::sqrt(a * b) : 0.5 * (a + b));
    h.pdf.push_back(h.counts[i] / (double(h.n) * (b - a)));
  }
  return h;
}

double kolmogorov_q(double lambda) {
  if (lambda < 0.2) return 1.0;  // the series converges slowly there; Q = 1 - O(1e-20)
  double sum = 0, sign = 1;
  for (int j = 1; j <= 100; ++j) {
    const double term = sign * std::exp(-2.0 * j * j * lambda * lambda);
    sum += term;
    if (std::fabs(term) < 1e-16 * std::fabs(sum)) break;
    sign = -sign;
  }
  return std::clamp(2 * sum, 0.0, 1.0);
}

namespace {
// p-value with Stephens' small-sample correction (Numerical Recipes 14.3); the
// critical distance is the asymptotic c(alpha) / sqrt(n_eff), c = sqrt(-ln(alpha/2)/2).
Ks finish(double d, double ne, double alpha) {
  Ks k;
  k.d = d;
  k.n_eff = ne;
  const double sq = std::sqrt(ne);
  k.p = kolmogorov_q((sq + 0.12 + 0.11 / sq) * d);
  k.critical = std::sqrt(-0.5 * std::log(alpha / 2)) / sq;
  return k;
}
}  // namespace

Ks ks_two_sample(Vec a, Vec b, double alpha) {
  if (a.empty() || b.empty()) throw Error("KS needs two non-empty samples");
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  const double na = double(a.size()), nb = double(b.size());
  std::size_t i = 0, j = 0;
  double d = 0;
  while (i < a.size() && j < b.size()) {
    const double v = std::min(a[i], b[j]);
    while (i < a.size() && a[i] == v) ++i;  // ties step both CDFs together
    while (j < b.size() && b[j] == v) ++j;
    d = std::max(d, std::fabs(i / na - j / nb));
  }
  return finish(d, na * nb / (na + nb), alpha);
}

Ks ks_one_sample(Vec x, const std::function<double(double)>& cdf, double alpha) {
  if (x.empty()) throw Error("KS needs a non-empty sample");
  std::sort(x.begin(), x.end());
  const double n = double(x.size());
  double d = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double f = cdf(x[i]);
    d = std::max({d, std::fabs((i + 1) / n - f), std::fabs(f - i / n)});
  }
  return finish(d, n, alpha);
}

Vec autocorrelation(const Vec& x, std::size_t max_lag) {
  const std::size_t n = x.size();
  if (n < 2) throw Error("autocorrelation needs at least 2 values");
  max_lag = std::min(max_lag, n - 1);
  std::size_t m = 1;
  while (m < 2 * n) m *= 2;  // zero padding: circular correlation = linear one
  const double mean = mean_of(x);
  std::vector<double> z(2 * m, 0.0);  // interleaved complex
  for (std::size_t i = 0; i < n; ++i) z[2 * i] = x[i] - mean;
  gsl_fft_complex_radix2_forward(z.data(), 1, m);
  for (std::size_t i = 0; i < m; ++i) {
    z[2 * i] = z[2 * i] * z[2 * i] + z[2 * i + 1] * z[2 * i + 1];
    z[2 * i + 1] = 0;
  }
  gsl_fft_complex_radix2_inverse(z.data(), 1, m);
  if (!(z[0] > 0)) throw Error("autocorrelation of a constant series");
  Vec c(max_lag + 1);
  for (std::size_t k = 0; k <= max_lag; ++k) c[k] = z[2 * k] / z[0];  // biased estimator, C(0) = 1
  return c;
}

double first_lag_below(const Vec& c, double thr) {
  for (std::size_t k = 1; k < c.size(); ++k) {
    if (c[k] >= thr) continue;
    const double a = c[k - 1], b = c[k];
    if (thr > 0 && b > 0)  // exact for an exponential decay
      return double(k - 1) + std::log(a / thr) / std::log(a / b);
    return double(k - 1) + (a - thr) / (a - b);
  }
  return -1;
}

CorrTime integrated_time(const Vec& c) {
  CorrTime t;
  double g = 1;
  for (std::size_t m = 1; m < c.size(); ++m) {
    g += 2 * c[m];
    t.g = g;
    t.window = m;
    if (double(m) >= 3 * g) break;
  }
  return t;
}

BlockError block_error(const Vec& x, std::size_t block) {
  BlockError r;
  const std::size_t n = x.size();
  r.g = integrated_time(autocorrelation(x, n / 2)).g;
  r.block = block ? block : static_cast<std::size_t>(std::ceil(10 * std::max(r.g, 1.0)));
  r.nblocks = n / r.block;
  if (r.nblocks < 4)
    throw Error("block-error: " + std::to_string(n) + " values make " + std::to_string(r.nblocks) +
                " blocks of " + std::to_string(r.block) + " (need at least 4; the series is too short for its correlation time)");
  Vec means(r.nblocks, 0.0);
  for (std::size_t b = 0; b < r.nblocks; ++b) {
    for (std::size_t i = 0; i < r.block; ++i) means[b] += x[b * r.block + i];
    means[b] /= double(r.block);
  }
  r.mean = mean_of(means);
  double var = 0, var_all = 0;
  for (double m : means) var += (m - r.mean) * (m - r.mean);
  var /= double(r.nblocks - 1);
  const double mx = mean_of(x);
  for (double v : x) var_all += (v - mx) * (v - mx);
  var_all /= double(n - 1);
  r.error = std::sqrt(var / double(r.nblocks));
  r.error_of_error = r.error / std::sqrt(2.0 * double(r.nblocks - 1));
  r.naive = std::sqrt(var_all / double(n));
  return r;
}

}  // namespace sable::analysis
