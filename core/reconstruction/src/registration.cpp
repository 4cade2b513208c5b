#include "keyturn/reconstruction/registration.h"

#include "open3d_plugin.h"

namespace keyturn::reconstruction {

const char* poseModelName(PoseModel m) { return m == PoseModel::Free ? "free" : "turntable"; }

RegistrationResult registerViews(const std::vector<RegistrationView>& views, const RegistrationOptions& options,
                                 const RegistrationProgress& progress) {
  RegistrationResult result;
  int kind = 0;
  const std::string error = detail::open3d().register_views(views, options, progress, result, kind);
  if (kind == 2) throw NoOverlapError(error);
  if (kind != 0) throw Error(error);
  return result;
}

}  // namespace keyturn::reconstruction
