#pragma once
// BigBIRD-layout files for the import tests, written with the HDF5 C library as the dataset's own
// tools write them (rig/src/h5_file.cpp reads them; this is an independent writer).
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "keyturn/core/depth_image.h"

namespace keyturn::test {

enum class H5Type { Float64, UInt16, Int16, Float32 };

struct H5Dataset {
  std::string name;
  H5Type type = H5Type::Float64;
  std::vector<unsigned long long> dims;  // {} = a scalar
  std::vector<double> values;            // row-major, converted to `type` by the library
};

void writeH5(const std::string& path, const std::vector<H5Dataset>& datasets);

// One matrix as a float64 dataset of its shape, row-major as h5py stores numpy arrays.
H5Dataset h5Matrix(const std::string& name, const Eigen::MatrixXd& m);
// A depth image as BigBIRD's "depth": uint16, height × width.
H5Dataset h5Depth(const std::vector<std::uint16_t>& depth, std::uint32_t width, std::uint32_t height);

// A P4 (binary) PBM: 1 = black.
void writePbm(const std::string& path, const std::vector<std::uint8_t>& black, std::uint32_t width, std::uint32_t height);

// A camera ← table transform: the table (z up) `distance` metres in front of a camera looking down
// on it at `elevation_deg`, turned `angle_deg` about its z axis. BigBIRD's pose file holds the
// inverse for NP5, and calibration.h5 H_NPi_ir_from_NP5 = cameraFromTable(0, e_i) · tableFromCamera(0, e_5).
Eigen::Matrix4d cameraFromTable(double angle_deg, double elevation_deg, double distance = 0.9);

constexpr double kNp5ElevationDeg = 80;  // the reference camera, the top one

// One Carmine of a fixture: its depth and colour cameras (the colour one 2.5 cm to the depth one's left).
struct FixtureCamera {
  int np = 1;  // NP1 … NP5
  double elevation_deg = 30;
  DepthIntrinsics depth_k{525, 525, 319.5, 239.5};
  double ir_depth_scale = 1;
  DepthIntrinsics rgb_k{1050, 1050, 639.5, 511.5};  // 1280 × 1024
};
Eigen::Matrix4d rgbFromIr();
// calibration.h5's datasets for these cameras: NPi_depth_K, NPi_rgb_K, NPi_ir_depth_scale,
// H_NPi_ir_from_NP5, H_NPi_from_NP5.
std::vector<H5Dataset> calibrationDatasets(const std::vector<FixtureCamera>& cameras);

}  // namespace keyturn::test
