#pragma once
// Test helper: run deck text (several lines) in a fresh Simulation, in memory.
#include <memory>
#include <sstream>
#include <string>

#include "core/input.h"
#include "core/simulation.h"

namespace sable::test {

struct Deck {
  std::unique_ptr<Simulation> sim = std::make_unique<Simulation>();
  std::unique_ptr<Input> in = std::make_unique<Input>(*sim);
  explicit Deck(bool quiet = true) {
    if (quiet) sim->screen = nullptr;
  }
  // Runs each line as a deck command; locations read "test:N".
  Deck& operator()(const std::string& text) {
    std::istringstream ss(text);
    std::string line;
    int n = 0;
    while (std::getline(ss, line)) in->one(line, DeckLocation{"test", ++n});
    return *this;
  }
  Simulation& operator*() { return *sim; }
  Simulation* operator->() { return sim.get(); }
};

}  // namespace sable::test
