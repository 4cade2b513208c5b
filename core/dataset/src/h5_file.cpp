#include "h5_file.h"

#include <hdf5.h>

#include <filesystem>

#include "keyturn/core/error.h"

namespace keyturn::dataset {
namespace {

// One HDF5 handle, closed by the function that fits its kind.
struct Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  ~Handle() {
    if (id >= 0) close(id);
  }
};

// The library's own error printing would put a stack of lines on stderr for every bad file.
void silenceLibrary() {
  static const bool once = [] { return H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr) >= 0; }();
  (void)once;
}

constexpr hsize_t kMaxSide = 1 << 14;  // no camera has a larger image; a corrupt shape is refused

}  // namespace

H5File::H5File(const std::string& path) : path_(path) {
  silenceLibrary();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path + ": no such file");
  if (H5Fis_hdf5(path.c_str()) <= 0) throw Error(path + ": not an HDF5 file");
  id_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id_ < 0) throw Error(path + ": corrupt HDF5 file (cannot be opened)");
}

H5File::~H5File() {
  if (id_ >= 0) H5Fclose(id_);
}

bool H5File::has(const std::string& dataset) const {
  if (H5Lexists(id_, dataset.c_str(), H5P_DEFAULT) <= 0) return false;
  const Handle object{H5Oopen(id_, dataset.c_str(), H5P_DEFAULT), H5Oclose};
  return object.id >= 0 && H5Iget_type(object.id) == H5I_DATASET;
}

Eigen::MatrixXd H5File::matrix(const std::string& name, int rows, int cols) const {
  const std::string what = path_ + ": dataset \"" + name + "\"";
  if (!has(name)) throw Error(what + " is missing");
  const Handle ds{H5Dopen2(id_, name.c_str(), H5P_DEFAULT), H5Dclose};
  if (ds.id < 0) throw Error(what + " cannot be opened (corrupt file?)");
  const Handle type{H5Dget_type(ds.id), H5Tclose};
  const H5T_class_t kind = H5Tget_class(type.id);
  if (kind != H5T_FLOAT && kind != H5T_INTEGER) throw Error(what + " is not numeric");
  const Handle space{H5Dget_space(ds.id), H5Sclose};
  const int rank = H5Sget_simple_extent_ndims(space.id);
  hsize_t dims[2] = {1, 1};
  if (rank < 0 || rank > 2 || H5Sget_simple_extent_dims(space.id, dims, nullptr) < 0)
    throw Error(what + " has an unreadable shape");
  const bool fits = rank == 2 ? dims[0] == hsize_t(rows) && dims[1] == hsize_t(cols)
                              : (rows == 1 || cols == 1) && (rank == 0 ? 1 : dims[0]) == hsize_t(rows) * cols;
  if (!fits)
    throw Error(what + " has shape " + (rank == 2 ? std::to_string(dims[0]) + " × " + std::to_string(dims[1])
                                                  : std::to_string(rank == 0 ? 1 : dims[0])) +
                ", expected " + std::to_string(rows) + " × " + std::to_string(cols));
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> m(rows, cols);
  if (H5Dread(ds.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, m.data()) < 0)
    throw Error(what + " cannot be read (corrupt file?)");
  if (!m.allFinite()) throw Error(what + " holds a non-finite number");
  return m;
}

DepthPixels H5File::depth(const std::string& name) const {
  const std::string what = path_ + ": dataset \"" + name + "\"";
  if (!has(name)) throw Error(what + " is missing (not a BigBIRD depth image?)");
  const Handle ds{H5Dopen2(id_, name.c_str(), H5P_DEFAULT), H5Dclose};
  if (ds.id < 0) throw Error(what + " cannot be opened (corrupt file?)");
  const Handle type{H5Dget_type(ds.id), H5Tclose};
  if (H5Tget_class(type.id) != H5T_INTEGER || H5Tget_size(type.id) != 2 || H5Tget_sign(type.id) != H5T_SGN_NONE)
    throw Error(what + " is not 16-bit unsigned (uint16 depth expected)");
  const Handle space{H5Dget_space(ds.id), H5Sclose};
  hsize_t dims[2] = {0, 0};
  if (H5Sget_simple_extent_ndims(space.id) != 2 || H5Sget_simple_extent_dims(space.id, dims, nullptr) < 0)
    throw Error(what + " is not a two-dimensional image");
  if (dims[0] == 0 || dims[1] == 0 || dims[0] > kMaxSide || dims[1] > kMaxSide)
    throw Error(what + " has shape " + std::to_string(dims[0]) + " × " + std::to_string(dims[1]) +
                " (expected rows × columns, each 1 to " + std::to_string(kMaxSide) + ")");
  DepthPixels d;
  d.height = static_cast<std::uint32_t>(dims[0]);
  d.width = static_cast<std::uint32_t>(dims[1]);
  d.values.resize(std::size_t(d.width) * d.height);
  if (H5Dread(ds.id, H5T_NATIVE_UINT16, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.values.data()) < 0)
    throw Error(what + " cannot be read (truncated or corrupt file)");
  return d;
}

}  // namespace keyturn::dataset
