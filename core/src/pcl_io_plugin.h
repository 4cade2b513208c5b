#pragma once
// PCL's PCD reader and PCD/PLY writers (libpcl_io, with the VTK and OpenNI libraries it pulls in:
// ~0.04 s of loading) are called from the plugin "pcl_io" (plugins/pcl_cloud_files.cpp), loaded by
// the first PCD read or cloud write. Internal to keyturn_core.
#include <pcl/PCLPointCloud2.h>

#include <string>

namespace keyturn::detail {

struct PclIo {
  // PCL's PCDReader::read: its result (< 0: failed); an exception of PCL's becomes `error`, -2.
  int (*read_pcd)(const std::string& path, pcl::PCLPointCloud2& blob, std::string& error);
  int (*write_ply)(const std::string& path, const pcl::PCLPointCloud2& blob);  // binary
  int (*write_pcd)(const std::string& path, const pcl::PCLPointCloud2& blob, int encoding);  // PcdEncoding
};

const PclIo& pclIo();

using PclIoFunction = const PclIo*();

}  // namespace keyturn::detail
