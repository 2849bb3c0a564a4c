// particletemplate/sphere `radius gaussian number MU SIGMA cut K` (sable
// extension for petit2017's +-1 sigma radii): draws against the analytic
// moments of a normal truncated at +-K sigma; LIGGGHTS' default kept; errors.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/engine/error.h"
#include "fixes/fix_particletemplate_sphere.h"
#include "tests/unit/deck_runner.h"

// A namespace per file: the unit tests compile in unity batches (tests/CMakeLists.txt).
namespace test_particletemplate_cut {

using sable::test::Deck;
using sable::test::error_of;

namespace {

const char* kBox2d = R"(units si
atom_style granular
dimension 2
boundary p f p
region box block 0 1 0 1 -0.5 0.5 units box
create_box 1 box
)";

// Variance of a normal truncated at +-K sigma over sigma^2 (standard result).
double variance_factor(double K) {
  const double phi = std::exp(-0.5 * K * K) / std::sqrt(2 * std::numbers::pi);
  const double mass = std::erf(K / std::sqrt(2.0));  // 2 Phi(K) - 1
  return 1 - 2 * K * phi / mass;
}

sable::FixParticletemplateSphere& tmpl(Deck& d, const std::string& line) {
  d(line);
  auto* f = dynamic_cast<sable::FixParticletemplateSphere*>(d->find_fix("pt"));
  EXPECT_NE(f, nullptr);
  return *f;
}

struct Moments {
  double mean = 0, var = 0, lo = 1e300, hi = -1e300;
};

Moments sample(sable::FixParticletemplateSphere& f, long n) {
  Moments m;
  double s = 0, s2 = 0;
  for (long i = 0; i < n; ++i) {
    const double r = f.draw().radius;
    s += r, s2 += r * r;
    m.lo = std::min(m.lo, r), m.hi = std::max(m.hi, r);
  }
  m.mean = s / n;
  m.var = s2 / n - m.mean * m.mean;
  return m;
}

}  // namespace

// delta = 0.5, cut 1: 200 000 draws. Tolerances 5 standard errors: the mean's
// sd/sqrt(n); the variance's sqrt(mu4/n) <= (K sigma)^2/sqrt(n) since |r - mu| <= K sigma.
// The untruncated variance (0.0625) or the +-3 sigma one would miss by > 100 tolerances.
TEST(TemplateCut, GaussianCutAtOneSigmaHasTruncatedMoments) {
  Deck d;
  d(kBox2d);
  auto& f = tmpl(d, "fix pt all particletemplate/sphere 15485863 density constant 1 radius gaussian number 1.0 0.25 cut 1");
  const long n = 200000;
  const double mu = 1.0, sigma = 0.25, K = 1.0;
  const Moments m = sample(f, n);
  const double var = sigma * sigma * variance_factor(K);
  EXPECT_NEAR(variance_factor(1.0), 0.29112, 1e-5);  // tabulated: 1 - 2 phi(1) / 0.682689
  EXPECT_NEAR(m.mean, mu, 5 * std::sqrt(var / n));
  EXPECT_NEAR(m.var, var, 5 * (K * sigma) * (K * sigma) / std::sqrt(double(n)));
  EXPECT_GE(m.lo, mu - K * sigma);
  EXPECT_LE(m.hi, mu + K * sigma);
  EXPECT_LT(m.lo, mu - 0.99 * K * sigma);  // the cut, not a narrower law, bounds the draws
  EXPECT_GT(m.hi, mu + 0.99 * K * sigma);
  EXPECT_DOUBLE_EQ(f.radius.max(), mu + K * sigma);
  // The template's expectancies use the truncated law: E[r^2] = mu^2 + var (2D area).
  EXPECT_NEAR(f.volume_expect(), std::numbers::pi * (mu * mu + var), 1e-12);
}

// A wide cut (K = 2, delta = 0.3) with mu - 3 sigma < 0 allowed because of the cut.
TEST(TemplateCut, CutTwoSigmaAllowsWideLaw) {
  Deck d;
  d(kBox2d);
  auto& f = tmpl(d, "fix pt all particletemplate/sphere 15485863 density constant 1 radius gaussian number 1.0 0.4 cut 2");
  const long n = 200000;
  const double sigma = 0.4, K = 2.0, var = sigma * sigma * variance_factor(K);
  const Moments m = sample(f, n);
  EXPECT_NEAR(m.mean, 1.0, 5 * std::sqrt(var / n));
  EXPECT_NEAR(m.var, var, 5 * (K * sigma) * (K * sigma) / std::sqrt(double(n)));
  EXPECT_GT(m.lo, 1.0 - K * sigma);
}

// Without `cut`, LIGGGHTS' meaning: +-3 sigma, untruncated expectancies, delta > 1/3 refused.
TEST(TemplateCut, DefaultStaysLiggghts) {
  Deck d;
  d(kBox2d);
  auto& f = tmpl(d, "fix pt all particletemplate/sphere 15485863 density constant 1 radius gaussian number 1.0 0.2");
  EXPECT_DOUBLE_EQ(f.radius.max(), 1.6);
  EXPECT_DOUBLE_EQ(f.radius.min(), 1.0 - 3 * 0.2);
  EXPECT_NEAR(f.volume_expect(), std::numbers::pi * (1.0 + 0.04), 1e-12);
  EXPECT_NE(error_of(d, "fix q all particletemplate/sphere 15485863 density constant 1 radius gaussian number 1.0 0.5")
                .find("mu - 3 sigma >= 0"),
            std::string::npos);
}

TEST(TemplateCut, BadCutsAreErrors) {
  Deck d;
  d(kBox2d);
  const std::string head = "fix q all particletemplate/sphere 15485863 density constant 1 radius gaussian number 1.0 0.7 ";
  const std::string e1 = error_of(d, head + "cut 1.5");
  EXPECT_NE(e1.find("mu - K sigma > 0"), std::string::npos) << e1;
  EXPECT_NE(e1.find("test:1"), std::string::npos) << e1;
  EXPECT_NE(e1.find("1.5"), std::string::npos) << e1;
  EXPECT_NE(error_of(d, head + "cut 0").find("between 0.1 and 10"), std::string::npos);
  EXPECT_NE(error_of(d, head + "cut x").find("the cut K"), std::string::npos);
  d(head + "cut 1");  // delta = 0.7 (petit2017's widest) with the +-1 sigma cut is fine
}

}  // namespace test_particletemplate_cut
