#pragma once
// What `balance` and `fix balance` share (core/input/command_balance.cpp).
#include <string>

#include "core/input/args.h"

namespace sable {

class Simulation;

struct BalanceShift {
  double thresh = 1;
  std::string dims;
};
// thresh shift dimstr Niter stopthresh, from word `at` on.
BalanceShift parse_balance_shift(const Simulation& sim, const Args& a, std::size_t at);
// The grid's cuts as fractions of the box, one line per axis the grid splits.
std::string cuts_text(const Simulation& sim);

}  // namespace sable
