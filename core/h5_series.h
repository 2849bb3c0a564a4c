#pragma once
// Output: HDF5 time series (fix ave/time, fix ave/histo, field outputs).
#include <cstdint>
#include <string>
#include <vector>

namespace sable {

// An HDF5 file of growing datasets (rows appended during the run). The file is
// open only while a row is written: each append opens it in SWMR-write mode,
// extends, writes, flushes and closes it. So the file of a killed run opens
// normally (h5py: File(name, 'r')) unless the kill fell inside an append, and
// then still opens with H5F_ACC_SWMR_READ (h5py: File(name, 'r', swmr=True)).
// Append the step dataset last: its length is the number of complete records.
class H5Series {
 public:
  explicit H5Series(const std::string& path);  // creates (truncates) the file
  H5Series(const H5Series&) = delete;
  H5Series& operator=(const H5Series&) = delete;
  ~H5Series();
  // Before start(): root attributes, constant datasets, growing datasets.
  void attribute(const std::string& name, const std::vector<std::string>& values);
  void constant(const std::string& name, const std::vector<double>& values);
  int series(const std::string& name, const std::vector<std::size_t>& row_shape, bool integer);
  void start();
  void append(int series, const double* row);
  void append(int series, std::int64_t value);  // integer series of scalars (steps)
  const std::string& path() const { return path_; }

 private:
  struct Series {
    std::string name;
    std::vector<unsigned long long> shape;  // row shape
    bool integer;
    unsigned long long rows = 0;
  };
  std::string path_;
  std::int64_t file_ = -1;
  std::vector<Series> series_;
  void append_raw(int series, const void* row);
};

}  // namespace sable
