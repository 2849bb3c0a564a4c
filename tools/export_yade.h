#pragma once
// sable --export-yade DECK -o script.py: runs the deck's set-up in sable
// (variables, loops, atoms, groups, set, velocity, fixes), and instead of
// stepping writes a YADE 2023 script for the same scene: bodies, materials
// and laws, engines, each `run N`, the thermo columns and the `print` lines
// (their variables translated to Python), so that sable_tools/compare.py
// reads YADE's screen as it reads sable's. What it cannot translate is an
// error naming the deck file, line and command. Conventions: README.md of
// reference_runs (YADE section).
#include <string>

namespace sable {

class Simulation;
class Input;

// Reads `deck` through `input` (whose Simulation is `sim`) and writes the YADE script to `out`.
void export_yade(Simulation& sim, Input& input, const std::string& deck, const std::string& out);

}  // namespace sable
