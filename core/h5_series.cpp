#include "core/h5_series.h"

#include <hdf5.h>

#include <algorithm>
#include <type_traits>

#include "core/error.h"

namespace sable {

static_assert(std::is_same_v<hid_t, std::int64_t>, "H5Series stores hid_t as int64_t");

namespace {
[[noreturn]] void h5fail(const std::string& path, const std::string& what) {
  fail("HDF5 file '" + path + "': cannot " + what);
}
}  // namespace

H5Series::H5Series(const std::string& path) : path_(path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // our messages instead of HDF5's error stack
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST);  // SWMR needs the latest format
  file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  if (file_ < 0) h5fail(path, "be created (is the directory writable, or the file open elsewhere?)");
}

H5Series::~H5Series() {
  if (file_ >= 0) H5Fclose(file_);
}

void H5Series::attribute(const std::string& name, const std::vector<std::string>& values) {
  std::vector<const char*> p;
  for (auto& v : values) p.push_back(v.c_str());
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  const hsize_t n = values.size();
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t attr = H5Acreate2(file_, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
  const bool ok = attr >= 0 && H5Awrite(attr, type, p.data()) >= 0;
  if (attr >= 0) H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
  if (!ok) h5fail(path_, "write attribute '" + name + "'");
}

void H5Series::constant(const std::string& name, const std::vector<double>& values) {
  const hsize_t n = values.size();
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t d = H5Dcreate2(file_, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const bool ok = d >= 0 && H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) >= 0;
  if (d >= 0) H5Dclose(d);
  H5Sclose(space);
  if (!ok) h5fail(path_, "write dataset '" + name + "'");
}

int H5Series::series(const std::string& name, const std::vector<std::size_t>& row_shape, bool integer) {
  Series s;
  s.integer = integer;
  std::vector<hsize_t> dims{0}, maxdims{H5S_UNLIMITED}, chunk{1};
  hsize_t row = 1;
  for (auto k : row_shape) {
    s.shape.push_back(k);
    dims.push_back(k);
    maxdims.push_back(k);
    chunk.push_back(k);
    row *= k;
  }
  chunk[0] = std::clamp<hsize_t>(8192 / std::max<hsize_t>(row, 1), 1, 1024);  // chunks of ~64 KiB at most
  const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), maxdims.data());
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data());
  const hid_t dset =
      H5Dcreate2(file_, name.c_str(), integer ? H5T_STD_I64LE : H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  H5Pclose(dcpl);
  H5Sclose(space);
  if (dset < 0) h5fail(path_, "create dataset '" + name + "'");
  H5Dclose(dset);
  s.name = name;
  series_.push_back(s);
  return static_cast<int>(series_.size()) - 1;
}

// Closed between appends, so that a killed run leaves a file marked consistent.
void H5Series::start() {
  if (H5Fclose(file_) < 0) h5fail(path_, "be closed after its layout was written");
  file_ = -1;
}

void H5Series::append_raw(int k, const void* row) {
  Series& s = series_[k];
  std::vector<hsize_t> dims{s.rows + 1}, start{s.rows}, count{1};
  for (auto d : s.shape) {
    dims.push_back(d);
    start.push_back(0);
    count.push_back(d);
  }
  const int rank = static_cast<int>(dims.size());
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST);
  const hid_t file = H5Fopen(path_.c_str(), H5F_ACC_RDWR | H5F_ACC_SWMR_WRITE, fapl);
  H5Pclose(fapl);
  if (file < 0) h5fail(path_, "be opened to append a record (was it moved or opened elsewhere?)");
  const hid_t dset = H5Dopen2(file, s.name.c_str(), H5P_DEFAULT);
  bool ok = dset >= 0 && H5Dset_extent(dset, dims.data()) >= 0;
  const hid_t fspace = H5Dget_space(dset);
  const hid_t mspace = H5Screate_simple(rank, count.data(), nullptr);
  ok = ok && H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr) >= 0;
  ok = ok && H5Dwrite(dset, s.integer ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE, mspace, fspace, H5P_DEFAULT, row) >= 0;
  ok = ok && H5Dflush(dset) >= 0;  // on disk now: a killed run keeps this row
  H5Sclose(mspace);
  H5Sclose(fspace);
  if (dset >= 0) H5Dclose(dset);
  ok = H5Fclose(file) >= 0 && ok;
  if (!ok) h5fail(path_, "append to a dataset (disk full?)");
  ++s.rows;
}

void H5Series::append(int k, const double* row) { append_raw(k, row); }
void H5Series::append(int k, std::int64_t value) { append_raw(k, &value); }

}  // namespace sable
