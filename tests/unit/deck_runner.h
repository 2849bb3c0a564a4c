#pragma once
// Test helper: run deck text (several lines) in a fresh Simulation, in memory.
#include <memory>
#include <sstream>
#include <string>

#include <algorithm>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include "core/engine/error.h"
#include "core/input/input.h"
#include "core/engine/neighbor.h"
#include "core/engine/simulation.h"

namespace sable::test {

struct Deck {
  std::unique_ptr<Simulation> sim = std::make_unique<Simulation>();
  std::unique_ptr<Input> in = std::make_unique<Input>(*sim);
  explicit Deck(bool quiet = true) {
    if (quiet) sim->screen = nullptr;
  }
  // Runs each line as a deck command; locations read "test:N".
  Deck& operator()(const std::string& text) {
    in->text("test", text);
    return *this;
  }
  Simulation& operator*() { return *sim; }
  Simulation* operator->() { return sim.get(); }
};

}  // namespace sable::test

namespace sable::test {

// Runs deck text and returns what it printed to the screen.
inline std::string printed(const std::string& text, Deck& d) {
  FILE* out = std::tmpfile();
  d->screen = out;
  d(text);
  std::rewind(out);
  std::string s;
  char buf[1024];
  while (std::fgets(buf, sizeof buf, out)) s += buf;
  std::fclose(out);
  d->screen = nullptr;
  return s;
}


// Pair history per list entry (zeros where not in contact), in entry order.
inline std::vector<double> entry_history(const ContactStore& s) {
  std::vector<double> out(s.row.size() * s.size, 0.0);
  for (std::size_t k = 0; k < s.row.size(); ++k)
    if (const double* h = s.history(k)) std::copy(h, h + s.size, out.begin() + k * s.size);
  return out;
}

// The message of the error a deck line raises, or "(no error)".
inline std::string error_of(Deck& d, const std::string& text) {
  try {
    d(text);
  } catch (const SableError& e) {
    return e.what();
  }
  return "(no error)";
}

// A fresh folder for the running test, removed with everything in it at the end.
struct TempDir {
  std::filesystem::path dir;
  TempDir() {
    const auto* t = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = std::filesystem::temp_directory_path() /
          ("sable_" + std::string(t->test_suite_name()) + "_" + t->name() + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  ~TempDir() { std::filesystem::remove_all(dir); }
  std::string operator/(const std::string& f) const { return (dir / f).string(); }
};

}  // namespace sable::test
