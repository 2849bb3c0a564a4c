#pragma once
// LAMMPS' shrink-wrapped boundaries (`boundary` styles s and m, per face):
// at each setup and neighbour rebuild such a face moves to the atoms' extent
// plus 1e-4 of the box's length at its first run; with m the box never gets
// smaller than it was then (create_box, or the box a restart file holds).
// Grains falling out of an m box stay in the run, as in LIGGGHTS. Kept beside
// the Domain (keyed by the Simulation) so that it touches no widely included header.
namespace sable {

class Simulation;

enum class FaceStyle : char { Fixed, Shrink, ShrinkMin };  // f, s, m
void set_face_style(const Simulation& sim, int axis, int side, FaceStyle s);  // side 0: lo, 1: hi
// Moves the wrapped faces to the atoms' extent (before the lost-atom check).
void shrink_wrap(Simulation& sim);
void forget_face_styles(const Simulation& sim);  // the Simulation ends

}  // namespace sable
