#pragma once
// The global-output role of a fix: the values a deck reads as f_ID, f_ID[i]
// and f_ID[i][j] (thermo columns, variables, fix ave/*). A fix gives its shape
// (scalar_flag, vector_size, array_rows x array_cols; all 0: no output) and
// the values on demand. Readers take a GlobalOutput, never a fix style.
namespace sable {

class GlobalOutput {
 public:
  int scalar_flag = 0, vector_size = 0;
  int array_rows = 0, array_cols = 0;  // LAMMPS' fix rigid: one row per body
  virtual double compute_scalar() { return 0.0; }
  virtual double compute_vector(int /*i*/) { return 0.0; }         // 1-based
  virtual double compute_array(int /*i*/, int /*j*/) { return 0.0; }  // 1-based

 protected:
  ~GlobalOutput() = default;  // owned and deleted as the fix it is part of
};

}  // namespace sable
