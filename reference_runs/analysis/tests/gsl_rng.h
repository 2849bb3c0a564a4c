#pragma once
// A seeded GSL generator for the analysis tests (one definition: they compile in one unity batch).
#include <gsl/gsl_rng.h>

#include <memory>

struct Rng {
  std::unique_ptr<gsl_rng, void (*)(gsl_rng*)> r{gsl_rng_alloc(gsl_rng_mt19937), gsl_rng_free};
  explicit Rng(unsigned long seed) { gsl_rng_set(r.get(), seed); }
  operator gsl_rng*() const { return r.get(); }
};
