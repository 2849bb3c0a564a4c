#pragma once
// The global-output role of a fix or a compute: the values a deck reads as
// f_ID / c_ID, [i] and [i][j] (thermo columns, variables, fix ave/*). A style
// gives its shape (scalar_flag, vector_size, array_rows x array_cols; all 0:
// no output) and the values on demand. Readers find it with find_global_output
// and read global(): never a style, nor whether it is a fix or a compute.
#include <string>

namespace sable {

class Simulation;

class GlobalOutput {
 public:
  int scalar_flag = 0, vector_size = 0;
  int array_rows = 0, array_cols = 0;  // LAMMPS' fix rigid: one row per body
  virtual double compute_scalar() { return 0.0; }
  virtual double compute_vector(int /*i*/) { return 0.0; }         // 1-based
  virtual double compute_array(int /*i*/, int /*j*/) { return 0.0; }  // 1-based

  // Whether [index][col] exists (index 0: the scalar; col 0: not an array element).
  bool has_global(int index, int col = 0) const {
    if (col) return index >= 1 && index <= array_rows && col >= 1 && col <= array_cols;
    return index == 0 ? scalar_flag != 0 : index >= 1 && index <= vector_size;
  }
  // The value a reader asks for (a compute evaluates once per step: Compute overrides).
  virtual double global(int index, int col = 0) {
    return col ? compute_array(index, col) : index ? compute_vector(index) : compute_scalar();
  }

 protected:
  ~GlobalOutput() = default;  // owned and deleted as the fix it is part of
};

// c_ID (kind 'c') or f_ID (kind 'f'); nullptr when none has that ID.
GlobalOutput* find_global_output(Simulation& sim, char kind, const std::string& id);
// "compute ID" or "fix ID", for messages.
std::string global_output_name(char kind, const std::string& id);

}  // namespace sable
