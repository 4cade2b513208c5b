// PCL-backed point cloud I/O (PCL's reader and writers in the plugin "pcl_io", src/pcl_io_plugin.h).
// PCL's own console messages are silenced: every failure becomes one keyturn::Error line naming
// the file and the problem.
#include "keyturn/core/cloud_io.h"

#include <fcntl.h>
#include <pcl/PCLPointCloud2.h>
#include <pcl/console/print.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "keyturn/core/durable_file.h"
#include "keyturn/core/error.h"
#include "keyturn/core/ply_reader.h"
#include "keyturn/core/plugin.h"
#include "keyturn/core/radius_search.h"
#include "file_error.h"
#include "pcl_io_plugin.h"
#include "quiet_pcl.h"

namespace fs = std::filesystem;

namespace keyturn {

namespace detail {
const PclIo& pclIo() {
  static const PclIo* table = pluginFunction<PclIoFunction>("pcl_io", "keyturn_pcl_io")();
  return *table;
}
}  // namespace detail

namespace {

// A point keyturn can work with: finite, and within kMaxCoordinate of the origin (farther, float
// squared distances between points overflow). Others are read as invalid, as NaN and inf are.
bool measurable(const Eigen::Vector3f& p) { return p.allFinite() && p.cwiseAbs().maxCoeff() <= kMaxCoordinate; }

}  // namespace

void detail::quietPcl() {
  static const bool once = [] {
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
    return true;
  }();
  (void)once;
}

namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

using detail::fail;  // "PATH: what", printable

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
    if (!measurable(cloud.points[i])) cloud.points[i].setConstant(std::nanf(""));
    if (famp) cloud.amplitude[i] = static_cast<float>(readScalar(rec + famp->offset, famp->datatype));
    if (fconf) cloud.confidence[i] = static_cast<float>(readScalar(rec + fconf->offset, fconf->datatype));
  }
  return cloud;
}

namespace {

// What a PCD header promises, read from its text before PCL sees the file:
// PCL's reader allocates for the promised points first, so a corrupt or
// truncated header must be caught here.
struct PcdPromise {
  std::uint64_t points = 0;
  std::uint64_t point_step = 0;  // bytes per point (binary)
  std::uint64_t values = 0;      // values per point (ascii)
  std::string data;              // ascii | binary | binary_compressed
  std::uint64_t data_offset = 0;
};

// PCL's PCDReader::readHeader goes on reading header lines after DATA, skipping comments and
// blank lines, as long as a line starts with a keyword (by prefix): a second "DATA" without its
// type made it throw std::out_of_range, a "POINTS" or "FIELDS" there would redefine the cloud.
// Such a line (where the data should start) is refused, as PCL would see it.
void rejectHeaderAfterData(const std::string& path, std::istream& in, int data_line) {
  static const char* keywords[] = {"VERSION", "FIELDS", "COLUMNS", "SIZE",   "TYPE", "COUNT",
                                   "WIDTH",   "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
  const std::streampos data = in.tellg();
  std::string line;
  for (int n = data_line + 1; n < data_line + 64 && std::getline(in, line); ++n) {
    std::istringstream ls(line);
    std::string key;
    if (!(ls >> key) || key[0] == '#') continue;
    for (const char* k : keywords)
      if (key.compare(0, std::strlen(k), k) == 0)
        fail(path, "corrupt PCD header: line " + std::to_string(n) + " ('" + key.substr(0, 20) +
                       "') is a header line after DATA (line " + std::to_string(data_line) + ")");
    break;
  }
  in.clear();
  in.seekg(data);
}

PcdPromise readPcdPromise(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  PcdPromise p;
  std::vector<std::uint64_t> sizes, counts;
  std::vector<std::string> fields, types;
  std::uint64_t width = 0, height = 0;
  std::string line;
  for (int n = 0; n < 64 && std::getline(in, line); ++n) {
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    // Only the keywords of the PCD format (PCL miscounts header lines otherwise).
    static const char* known[] = {"VERSION", "FIELDS", "COLUMNS", "SIZE", "TYPE", "COUNT",
                                  "WIDTH", "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
    if (!key.empty() && key[0] != '#' &&
        std::none_of(std::begin(known), std::end(known), [&](const char* k) { return key == k; }))
      fail(path, "not a valid PCD file (unknown header line " + std::to_string(n + 1) + ": '" + key.substr(0, 20) + "')");
    if (key == "FIELDS" || key == "COLUMNS") for (std::string f; ls >> f;) fields.push_back(f);
    else if (key == "TYPE") for (std::string t; ls >> t;) types.push_back(t);
    else if (key == "SIZE") for (std::uint64_t v; ls >> v;) sizes.push_back(v);
    else if (key == "COUNT") for (std::uint64_t v; ls >> v;) counts.push_back(v);
    else if (key == "WIDTH") ls >> width;
    else if (key == "HEIGHT") ls >> height;
    else if (key == "POINTS") ls >> p.points;
    else if (key == "DATA") {
      ls >> p.data;
      p.data_offset = static_cast<std::uint64_t>(in.tellg());
      rejectHeaderAfterData(path, in, n + 1);
      break;
    }
  }
  if (p.data.empty() || sizes.empty() || fields.empty())
    fail(path, "not a valid PCD file (no FIELDS/SIZE/DATA header)");
  // PCL indexes these lines by field without checking: they must agree.
  if (sizes.size() != fields.size() || types.size() != fields.size() || (!counts.empty() && counts.size() != fields.size()))
    fail(path, "corrupt PCD header: FIELDS, SIZE, TYPE and COUNT list different numbers of fields");
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const std::uint64_t sz = sizes[i];
    const std::string& t = types[i];
    if ((sz != 1 && sz != 2 && sz != 4 && sz != 8) || (t != "F" && t != "I" && t != "U") || (t == "F" && sz < 4))
      fail(path, "corrupt PCD header: field '" + fields[i] + "' has TYPE " + t + " and SIZE " + std::to_string(sz));
    if (!counts.empty() && (counts[i] == 0 || counts[i] > 4096))
      fail(path, "corrupt PCD header: field '" + fields[i] + "' has COUNT " + std::to_string(counts[i]));
  }
  if (width * height != p.points && width != 0)
    fail(path, "corrupt PCD header: WIDTH × HEIGHT = " + std::to_string(width * height) +
                   " but POINTS = " + std::to_string(p.points));
  if (p.points == 0) fail(path, "empty point cloud (0 points)");
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const std::uint64_t c = i < counts.size() ? counts[i] : 1;
    p.point_step += sizes[i] * c;
    p.values += c;
  }
  return p;
}

void checkPcdPayload(const std::string& path, const PcdPromise& p, std::uintmax_t file_size) {
  const std::uint64_t room = file_size > p.data_offset ? file_size - p.data_offset : 0;
  const std::string promise = "header promises " + std::to_string(p.points) + " points";
  if (p.data == "ascii") {
    // Every ascii value takes at least one character and one separator.
    if (p.points > (room + 1) / (2 * std::max<std::uint64_t>(p.values, 1)))
      fail(path, "truncated PCD: " + promise + " but only " + std::to_string(room) +
                     " bytes of ascii data follow");
  } else if (p.data == "binary") {
    if (p.points > room / std::max<std::uint64_t>(p.point_step, 1))
      fail(path, "truncated PCD: " + promise + " (" + std::to_string(p.points * p.point_step) +
                     " bytes of data) but the file has " + std::to_string(room));
  } else if (p.data == "binary_compressed") {
    std::ifstream in(path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(p.data_offset));
    std::uint32_t sizes[2] = {0, 0};
    in.read(reinterpret_cast<char*>(sizes), sizeof(sizes));
    if (!in) fail(path, "truncated PCD: compressed data header missing");
    if (8ull + sizes[0] > room)
      fail(path, "truncated PCD: compressed block of " + std::to_string(sizes[0]) +
                     " bytes but the file ends after " + std::to_string(room - 8));
    if (sizes[1] != p.points * p.point_step)
      fail(path, "corrupt PCD: compressed block unpacks to " + std::to_string(sizes[1]) +
                     " bytes, the header needs " + std::to_string(p.points * p.point_step));
  } else {
    fail(path, "not a valid PCD file (unknown DATA type '" + p.data + "')");
  }
}

Cloud loadPcd(const std::string& path, std::uintmax_t file_size) {
  checkPcdPayload(path, readPcdPromise(path), file_size);
  pcl::PCLPointCloud2 blob;
  std::string error;
  const int read = detail::pclIo().read_pcd(path, blob, error);
  if (!error.empty()) fail(path, "corrupt PCD: PCL's reader failed (" + error + ")");
  if (read < 0) fail(path, "corrupt PCD: PCL could not read the point data");
  if (blob.fields.empty()) fail(path, "not a valid PCD file (no fields)");
  return cloudFromPclBlob(path, blob);
}

// Organized clouds keep their grid: PCL's writer records it as obj_info num_cols/num_rows.
void applyGrid(const PlyData& ply, Cloud& cloud) {
  std::size_t cols = 0, rows = 0;
  for (const auto& info : ply.obj_info) {
    std::istringstream ls(info);
    std::string key;
    long long v = 0;
    if (!(ls >> key >> v) || v <= 0) continue;
    if (key == "num_cols") cols = static_cast<std::size_t>(v);
    if (key == "num_rows") rows = static_cast<std::size_t>(v);
  }
  // Divided, not multiplied: two huge header values can multiply (mod 2^64) to the point count.
  const std::size_t n = cloud.points.size();
  if (cols != 0 && rows != 0 && n % cols == 0 && n / cols == rows) {
    cloud.width = static_cast<std::uint32_t>(cols);
    cloud.height = static_cast<std::uint32_t>(rows);
  }
}

Cloud loadPly(const std::string& path) {
  const PlyData ply = readPly(path);
  const PlyElement* vertex = ply.find("vertex");
  if (!vertex) fail(path, "PLY file has no vertex element");
  if (vertex->count == 0) fail(path, "empty point cloud (0 vertices)");
  // A mesh's vertices are not what a camera sees (no occlusion, no noise, object coordinates).
  if (const PlyElement* face = ply.find("face"); face && face->count > 0)
    fail(path, "is a mesh (" + std::to_string(face->count) + " faces), not a camera view: render views of it first "
               "(keyturn render)");
  const PlyProperty* x = vertex->find("x");
  const PlyProperty* y = vertex->find("y");
  const PlyProperty* z = vertex->find("z");
  if (!x || !y || !z || x->is_list || y->is_list || z->is_list) fail(path, "no x/y/z fields");
  const PlyProperty* amp = vertex->find("amplitude");
  if (!amp) amp = vertex->find("intensity");
  const PlyProperty* conf = vertex->find("confidence");
  if (amp && amp->is_list) amp = nullptr;
  if (conf && conf->is_list) conf = nullptr;

  const std::size_t n = vertex->count;
  Cloud cloud;
  cloud.width = static_cast<std::uint32_t>(n);
  cloud.height = 1;
  cloud.points.resize(n);
  if (amp) cloud.amplitude.resize(n);
  if (conf) cloud.confidence.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    cloud.points[i] = Eigen::Vector3d(x->values[i], y->values[i], z->values[i]).cast<float>();
    if (!measurable(cloud.points[i])) cloud.points[i].setConstant(std::nanf(""));
    if (amp) cloud.amplitude[i] = static_cast<float>(amp->values[i]);
    if (conf) cloud.confidence[i] = static_cast<float>(conf->values[i]);
  }
  applyGrid(ply, cloud);
  return cloud;
}

}  // namespace

Cloud loadCloud(const std::string& path, const DepthImageOptions& depth) {
  detail::quietPcl();
  std::error_code ec;
  if (!fs::exists(path, ec)) fail(path, "no such file");
  if (fs::is_directory(path, ec)) fail(path, "is a directory, expected a .pcd, .ply or depth .png file");
  const auto size = fs::file_size(path, ec);
  if (ec) fail(path, "cannot read file size: " + ec.message());
  if (size == 0) fail(path, "empty file (0 bytes)");
  if (::access(path.c_str(), R_OK) != 0) fail(path, "permission denied");
  const std::string ext = lowerExtension(path);
  Cloud cloud;
  if (ext == ".pcd") cloud = loadPcd(path, size);
  else if (ext == ".ply") cloud = loadPly(path);
  else if (ext == ".png") cloud = loadDepthImage(path, depth);
  else fail(path, "unsupported format '" + ext + "' (expected .pcd, .ply or a 16-bit depth .png)");
  return cloud;
}

void saveCloud(const std::string& path, const Cloud& cloud, PcdEncoding encoding) {
  detail::quietPcl();
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

  writeFileDurablyWith(path, [&](const std::string& tmp) {
    const int rc = lowerExtension(path) == ".ply" ? detail::pclIo().write_ply(tmp, blob)
                                                  : detail::pclIo().write_pcd(tmp, blob, static_cast<int>(encoding));
    if (rc < 0) fail(path, "could not write the point cloud");
  });
}

}  // namespace keyturn
