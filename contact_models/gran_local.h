#pragma once
// Columns of compute pair/gran/local and wall/gran/local (LIGGGHTS
// compute_pair_gran_local.txt): keywords pos vel id force force_normal
// force_tangential torque history contactArea delta, always written in that
// order whatever order they are given in. No keyword = LIGGGHTS' default set
// (pos vel id force torque history contactArea).
#include <string>
#include <vector>

#include "core/engine/neighbor.h"

namespace sable {

class Args;

struct GranLocalColumns {
  bool pos = true, vel = true, id = true, force = true, fn = false, ft = false, torque = true, history = true,
       area = true, delta = false;
  bool history_explicit = false;

  void parse(const Args& a, std::size_t from);
  // Column names for a model with these history slots; for walls "1" is the wall side.
  std::vector<std::string> names(const std::vector<HistorySlot>& slots) const;

  // Appends one row. p1/p2, v1/v2: the two positions / velocities (pair: i, j;
  // wall: wall point, grain); ids: three id columns; f, t: force and torque on
  // the grain i; en: unit normal; h: history; area, overlap.
  void row(std::vector<double>& out, const double* p1, const double* p2, const double* v1, const double* v2,
           const double ids[3], const double* f, const double* t, const double* en, const double* h, int nh,
           double area, double overlap) const;
};

}  // namespace sable
