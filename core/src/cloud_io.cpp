// PCL-backed point cloud I/O. PCL's own console messages are silenced: every
// failure becomes one keyturn::Error line naming the file and the problem.
#include "keyturn/core/cloud_io.h"

#include <fcntl.h>
#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "keyturn/core/error.h"

namespace fs = std::filesystem;

namespace keyturn {
namespace {

void quietPcl() {
  static const bool once = [] {
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
    return true;
  }();
  (void)once;
}

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw Error(path + ": " + what);
}

const pcl::PCLPointField* findField(const pcl::PCLPointCloud2& blob,
                                    std::initializer_list<const char*> names) {
  for (const char* name : names)
    for (const auto& f : blob.fields)
      if (f.name == name) return &f;
  return nullptr;
}

double readScalar(const std::uint8_t* at, std::uint8_t datatype) {
  switch (datatype) {
    case pcl::PCLPointField::INT8: { std::int8_t v; std::memcpy(&v, at, 1); return v; }
    case pcl::PCLPointField::UINT8: { std::uint8_t v; std::memcpy(&v, at, 1); return v; }
    case pcl::PCLPointField::INT16: { std::int16_t v; std::memcpy(&v, at, 2); return v; }
    case pcl::PCLPointField::UINT16: { std::uint16_t v; std::memcpy(&v, at, 2); return v; }
    case pcl::PCLPointField::INT32: { std::int32_t v; std::memcpy(&v, at, 4); return v; }
    case pcl::PCLPointField::UINT32: { std::uint32_t v; std::memcpy(&v, at, 4); return v; }
    case pcl::PCLPointField::FLOAT32: { float v; std::memcpy(&v, at, 4); return v; }
    case pcl::PCLPointField::FLOAT64: { double v; std::memcpy(&v, at, 8); return v; }
    default: return std::nan("");
  }
}

std::size_t fieldSize(std::uint8_t datatype) {
  switch (datatype) {
    case pcl::PCLPointField::INT8: case pcl::PCLPointField::UINT8: return 1;
    case pcl::PCLPointField::INT16: case pcl::PCLPointField::UINT16: return 2;
    case pcl::PCLPointField::FLOAT64: return 8;
    default: return 4;
  }
}

}  // namespace

Cloud cloudFromPclBlob(const std::string& path, const pcl::PCLPointCloud2& blob) {
  const auto* fx = findField(blob, {"x"});
  const auto* fy = findField(blob, {"y"});
  const auto* fz = findField(blob, {"z"});
  if (!fx || !fy || !fz) fail(path, "no x/y/z fields");
  const auto* famp = findField(blob, {"amplitude", "intensity"});
  const auto* fconf = findField(blob, {"confidence"});

  const std::size_t n = static_cast<std::size_t>(blob.width) * blob.height;
  if (blob.data.size() < n * blob.point_step) fail(path, "point data shorter than the header says");
  for (const auto* f : {fx, fy, fz, famp, fconf})
    if (f && f->offset + fieldSize(f->datatype) > blob.point_step)
      fail(path, "field '" + f->name + "' lies outside the point record");

  Cloud cloud;
  cloud.width = blob.width;
  cloud.height = blob.height;
  cloud.points.resize(n);
  if (famp) cloud.amplitude.resize(n);
  if (fconf) cloud.confidence.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* rec = blob.data.data() + i * blob.point_step;
    cloud.points[i] = Eigen::Vector3f(static_cast<float>(readScalar(rec + fx->offset, fx->datatype)),
                                      static_cast<float>(readScalar(rec + fy->offset, fy->datatype)),
                                      static_cast<float>(readScalar(rec + fz->offset, fz->datatype)));
    if (!cloud.points[i].allFinite()) cloud.points[i].setConstant(std::nanf(""));
    if (famp) cloud.amplitude[i] = static_cast<float>(readScalar(rec + famp->offset, famp->datatype));
    if (fconf) cloud.confidence[i] = static_cast<float>(readScalar(rec + fconf->offset, fconf->datatype));
  }
  return cloud;
}

namespace {

// PCL trusts the header; check that the file really holds the data it promises
// so a truncated file is named as such instead of failing somewhere inside PCL.
void checkPcdPayload(const std::string& path, const pcl::PCLPointCloud2& header, int data_type,
                     unsigned data_idx, std::uintmax_t file_size) {
  const std::uint64_t expected =
      static_cast<std::uint64_t>(header.width) * header.height * header.point_step;
  if (data_type == 1) {
    if (data_idx + expected > file_size)
      fail(path, "truncated PCD: header promises " + std::to_string(header.width * header.height) +
                     " points (" + std::to_string(expected) + " bytes of data) but the file has " +
                     std::to_string(file_size > data_idx ? file_size - data_idx : 0));
  } else if (data_type == 2) {
    std::ifstream in(path, std::ios::binary);
    in.seekg(data_idx);
    std::uint32_t sizes[2] = {0, 0};
    in.read(reinterpret_cast<char*>(sizes), sizeof(sizes));
    if (!in) fail(path, "truncated PCD: compressed data header missing");
    if (data_idx + 8ull + sizes[0] > file_size)
      fail(path, "truncated PCD: compressed block of " + std::to_string(sizes[0]) +
                     " bytes but the file ends after " + std::to_string(file_size - data_idx - 8));
    if (sizes[1] != expected)
      fail(path, "corrupt PCD: compressed block unpacks to " + std::to_string(sizes[1]) +
                     " bytes, header needs " + std::to_string(expected));
  }
}

Cloud loadPcd(const std::string& path, std::uintmax_t file_size) {
  pcl::PCDReader reader;
  pcl::PCLPointCloud2 header;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0, data_type = 0;
  unsigned int data_idx = 0;
  if (reader.readHeader(path, header, origin, orientation, version, data_type, data_idx) < 0)
    fail(path, "not a valid PCD file (header unreadable)");
  if (header.fields.empty()) fail(path, "not a valid PCD file (no FIELDS in the header)");
  if (header.width == 0 || header.height == 0) fail(path, "empty point cloud (0 points)");
  checkPcdPayload(path, header, data_type, data_idx, file_size);
  pcl::PCLPointCloud2 blob;
  if (reader.read(path, blob, origin, orientation, version) < 0)
    fail(path, "corrupt PCD: PCL could not read the point data");
  return cloudFromPclBlob(path, blob);
}

Cloud loadPly(const std::string& path) {
  pcl::PLYReader reader;
  pcl::PCLPointCloud2 blob;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0;
  if (reader.read(path, blob, origin, orientation, version) < 0)
    fail(path, "not a readable PLY file");
  if (blob.width * blob.height == 0) fail(path, "empty point cloud (0 vertices)");
  return cloudFromPclBlob(path, blob);
}

void syncFile(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

}  // namespace

Cloud loadCloud(const std::string& path) {
  quietPcl();
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(path, "no such file");
  if (fs::is_directory(path, ec)) fail(path, "is a directory, expected a .pcd or .ply file");
  const auto size = fs::file_size(path, ec);
  if (ec) fail(path, "cannot read file size: " + ec.message());
  if (size == 0) fail(path, "empty file (0 bytes)");
  if (::access(path.c_str(), R_OK) != 0) fail(path, "permission denied");
  const std::string ext = lowerExtension(path);
  Cloud cloud;
  if (ext == ".pcd") cloud = loadPcd(path, size);
  else if (ext == ".ply") cloud = loadPly(path);
  else fail(path, "unsupported format '" + ext + "' (expected .pcd or .ply)");
  return cloud;
}

void saveCloud(const std::string& path, const Cloud& cloud, PcdEncoding encoding) {
  quietPcl();
  if (cloud.points.empty()) fail(path, "refusing to write an empty cloud");
  pcl::PCLPointCloud2 blob;
  blob.width = cloud.width;
  blob.height = cloud.height;
  const bool amp = cloud.amplitude.size() == cloud.points.size();
  const bool conf = cloud.confidence.size() == cloud.points.size();
  std::vector<std::string> names = {"x", "y", "z"};
  if (amp) names.push_back("amplitude");
  if (conf) names.push_back("confidence");
  for (std::size_t k = 0; k < names.size(); ++k) {
    pcl::PCLPointField f;
    f.name = names[k];
    f.offset = static_cast<std::uint32_t>(4 * k);
    f.datatype = pcl::PCLPointField::FLOAT32;
    f.count = 1;
    blob.fields.push_back(f);
  }
  blob.point_step = static_cast<std::uint32_t>(4 * names.size());
  blob.row_step = blob.point_step * blob.width;
  blob.is_dense = cloud.validCount() == cloud.points.size();
  blob.data.resize(static_cast<std::size_t>(blob.point_step) * cloud.points.size());
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    float rec[5];
    std::size_t k = 0;
    rec[k++] = cloud.points[i].x();
    rec[k++] = cloud.points[i].y();
    rec[k++] = cloud.points[i].z();
    if (amp) rec[k++] = cloud.amplitude[i];
    if (conf) rec[k++] = cloud.confidence[i];
    std::memcpy(blob.data.data() + i * blob.point_step, rec, blob.point_step);
  }

  const fs::path target(path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  const std::string tmp = path + ".tmp";
  int rc = 0;
  if (lowerExtension(path) == ".ply") {
    pcl::PLYWriter writer;
    rc = writer.write(tmp, blob, Eigen::Vector4f::Zero(), Eigen::Quaternionf::Identity(), true, false);
  } else {
    pcl::PCDWriter writer;
    switch (encoding) {
      case PcdEncoding::Ascii: rc = writer.writeASCII(tmp, blob); break;
      case PcdEncoding::Binary: rc = writer.writeBinary(tmp, blob); break;
      case PcdEncoding::BinaryCompressed: rc = writer.writeBinaryCompressed(tmp, blob); break;
    }
  }
  if (rc < 0) {
    std::error_code ec;
    fs::remove(tmp, ec);
    fail(path, "could not write the point cloud");
  }
  syncFile(tmp);
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) fail(path, "could not move the written file into place: " + ec.message());
}

}  // namespace keyturn
