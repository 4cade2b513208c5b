#include "bigbird_files.h"

#include <hdf5.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <stdexcept>

namespace keyturn::test {

void writeH5(const std::string& path, const std::vector<H5Dataset>& datasets) {
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0) throw std::runtime_error(path + ": cannot create");
  for (const auto& d : datasets) {
    std::vector<hsize_t> dims(d.dims.begin(), d.dims.end());
    const hid_t space = dims.empty() ? H5Screate(H5S_SCALAR) : H5Screate_simple(int(dims.size()), dims.data(), nullptr);
    const hid_t type = d.type == H5Type::UInt16  ? H5T_STD_U16LE
                       : d.type == H5Type::Int16 ? H5T_STD_I16LE
                       : d.type == H5Type::Float32 ? H5T_IEEE_F32LE
                                                   : H5T_IEEE_F64LE;
    const hid_t props = H5Pcreate(H5P_DATASET_CREATE);
    if (dims.size() == 2 && d.type == H5Type::UInt16) {  // chunked and deflated, as BigBIRD's depth
      const hsize_t chunk[2] = {std::min<hsize_t>(dims[0], 64), std::min<hsize_t>(dims[1], 64)};
      H5Pset_chunk(props, 2, chunk);
      H5Pset_deflate(props, 4);
    }
    const hid_t ds = H5Dcreate2(file, d.name.c_str(), type, space, H5P_DEFAULT, props, H5P_DEFAULT);
    if (ds < 0 || H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.values.data()) < 0)
      throw std::runtime_error(path + ": cannot write " + d.name);
    H5Dclose(ds);
    H5Pclose(props);
    H5Sclose(space);
  }
  H5Fclose(file);
}

H5Dataset h5Matrix(const std::string& name, const Eigen::MatrixXd& m) {
  H5Dataset d{name, H5Type::Float64, {static_cast<unsigned long long>(m.rows()), static_cast<unsigned long long>(m.cols())}, {}};
  for (int r = 0; r < m.rows(); ++r)
    for (int c = 0; c < m.cols(); ++c) d.values.push_back(m(r, c));
  return d;
}

H5Dataset h5Depth(const std::vector<std::uint16_t>& depth, std::uint32_t width, std::uint32_t height) {
  return {"depth", H5Type::UInt16, {height, width}, std::vector<double>(depth.begin(), depth.end())};
}

void writePbm(const std::string& path, const std::vector<std::uint8_t>& black, std::uint32_t width, std::uint32_t height) {
  std::ofstream out(path, std::ios::binary);
  out << "P4\n# keyturn test mask\n" << width << " " << height << "\n";
  const std::size_t row = (width + 7) / 8;
  for (std::uint32_t v = 0; v < height; ++v) {
    std::vector<unsigned char> bits(row, 0);
    for (std::uint32_t u = 0; u < width; ++u)
      if (black[std::size_t(v) * width + u]) bits[u / 8] |= 0x80 >> (u % 8);
    out.write(reinterpret_cast<const char*>(bits.data()), std::streamsize(row));
  }
  if (!out) throw std::runtime_error(path + ": cannot write");
}

Eigen::Matrix4d cameraFromTable(double angle_deg, double elevation_deg, double distance) {
  // Rx(90° + e) takes the table's z (up) to (0, −cos e, −sin e): up and towards the camera.
  const Eigen::Affine3d m = Eigen::Translation3d(0.02, 0.05, distance) *
                            Eigen::AngleAxisd(M_PI / 2 + elevation_deg * M_PI / 180, Eigen::Vector3d::UnitX()) *
                            Eigen::AngleAxisd(angle_deg * M_PI / 180, Eigen::Vector3d::UnitZ());
  return m.matrix();
}

Eigen::Matrix4d rgbFromIr() {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m(0, 3) = 0.025;
  return m;
}

std::vector<H5Dataset> calibrationDatasets(const std::vector<FixtureCamera>& cameras) {
  auto k = [](const DepthIntrinsics& i) {
    Eigen::Matrix3d m;
    m << i.fx, 0, i.cx, 0, i.fy, i.cy, 0, 0, 1;
    return m;
  };
  std::vector<H5Dataset> out;
  const Eigen::Matrix4d np5_from_table = cameraFromTable(0, kNp5ElevationDeg);
  for (const auto& c : cameras) {
    const std::string np = "NP" + std::to_string(c.np);
    const Eigen::Matrix4d ir_from_np5 = cameraFromTable(0, c.elevation_deg) * np5_from_table.inverse();
    out.push_back(h5Matrix(np + "_depth_K", k(c.depth_k)));
    out.push_back(h5Matrix(np + "_rgb_K", k(c.rgb_k)));
    out.push_back({np + "_ir_depth_scale", H5Type::Float64, {1}, {c.ir_depth_scale}});
    out.push_back(h5Matrix("H_" + np + "_ir_from_NP5", ir_from_np5));
    out.push_back(h5Matrix("H_" + np + "_from_NP5", rgbFromIr() * ir_from_np5));
  }
  return out;
}

}  // namespace keyturn::test
