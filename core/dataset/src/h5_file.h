#pragma once
// Reading the HDF5 files BigBIRD ships (depth images, calibration, poses) through the HDF5 C
// library, whose headers only h5_file.cpp includes. Every failure, a corrupt or truncated file
// included, is one keyturn::Error naming the file and the dataset; the library prints nothing.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace keyturn::dataset {

struct DepthPixels {
  std::vector<std::uint16_t> values;  // row-major
  std::uint32_t width = 0, height = 0;
};

class H5File {
 public:
  explicit H5File(const std::string& path);  // opened read-only
  ~H5File();
  H5File(const H5File&) = delete;
  H5File& operator=(const H5File&) = delete;

  const std::string& path() const { return path_; }
  bool has(const std::string& dataset) const;
  // A numeric dataset of exactly rows × cols values (a (n,) or scalar dataset for one row or column),
  // as doubles, row-major as stored.
  Eigen::MatrixXd matrix(const std::string& dataset, int rows, int cols) const;
  // A two-dimensional 16-bit unsigned dataset (height × width), as BigBIRD's "depth".
  DepthPixels depth(const std::string& dataset) const;

 private:
  std::string path_;
  std::int64_t id_ = -1;  // hid_t
};

}  // namespace keyturn::dataset
