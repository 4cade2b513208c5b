// The plugin "pcl_io" (src/pcl_io_plugin.h): PCL's PCD reader and PCD/PLY writers.
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include "../src/pcl_io_plugin.h"
#include "keyturn/core/cloud_io.h"
#include "keyturn/core/plugin.h"

namespace {

int readPcd(const std::string& path, pcl::PCLPointCloud2& blob, std::string& error) {
  pcl::PCDReader reader;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0;
  try {
    return reader.read(path, blob, origin, orientation, version);
  } catch (const std::exception& e) {  // PCL's header parser indexes tokens with .at()
    error = e.what();
    return -2;
  }
}

int writePly(const std::string& path, const pcl::PCLPointCloud2& blob) {
  pcl::PLYWriter writer;
  return writer.write(path, blob, Eigen::Vector4f::Zero(), Eigen::Quaternionf::Identity(), true, false);
}

int writePcd(const std::string& path, const pcl::PCLPointCloud2& blob, int encoding) {
  pcl::PCDWriter writer;
  switch (static_cast<keyturn::PcdEncoding>(encoding)) {
    case keyturn::PcdEncoding::Ascii: return writer.writeASCII(path, blob);
    case keyturn::PcdEncoding::Binary: return writer.writeBinary(path, blob);
    case keyturn::PcdEncoding::BinaryCompressed: return writer.writeBinaryCompressed(path, blob);
  }
  return -1;
}

}  // namespace

KEYTURN_PLUGIN_EXPORT const keyturn::detail::PclIo* keyturn_pcl_io() {
  static const keyturn::detail::PclIo table{readPcd, writePly, writePcd};
  return &table;
}
