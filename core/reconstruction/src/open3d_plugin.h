#pragma once
// Open3D (libOpen3D 0.16 and the ~300 libraries it loads: too heavy for every start of keyturn)
// is called only from the plugin "open3d" (plugins/open3d_*.cpp), loaded by the first
// registration or surface. Internal to keyturn_reconstruction. Each entry returns an empty string
// or the reason it failed (no exception crosses the module boundary).
#include <string>
#include <vector>

#include "keyturn/reconstruction/registration.h"
#include "keyturn/reconstruction/surface.h"

namespace keyturn::reconstruction::detail {

struct Open3dFunctions {
  // error_kind: 0 none, 1 keyturn::Error, 2 NoOverlapError
  std::string (*register_views)(const std::vector<RegistrationView>& views, const RegistrationOptions& options,
                                const RegistrationProgress& progress, RegistrationResult& result, int& error_kind);
  std::string (*fuse_views)(const std::vector<FuseView>& views, const FuseOptions& options, OrientedPoints& out);
  std::string (*poisson)(const OrientedPoints& cloud, const PoissonOptions& options, Mesh& out);
  std::string (*load_mesh)(const std::string& path, Mesh& out);
  std::string (*distances_to_mesh)(const std::vector<Eigen::Vector3f>& points, const Mesh& reference,
                                   std::vector<double>& out);
  std::string (*sample_mesh)(const Mesh& mesh, std::size_t samples, std::vector<Eigen::Vector3f>& out);
  std::string (*tsdf)(const std::vector<DepthFrame>& frames, const OrientedPoints& points, const TsdfOptions& options,
                      Mesh& out);
};

const Open3dFunctions& open3d();

using Open3dFunctionsEntry = const Open3dFunctions*();

}  // namespace keyturn::reconstruction::detail
