#include "open3d_plugin.h"

#include "keyturn/core/plugin.h"

namespace keyturn::reconstruction::detail {

const Open3dFunctions& open3d() {
  static const Open3dFunctions* table = pluginFunction<Open3dFunctionsEntry>("open3d", "keyturn_open3d")();
  return *table;
}

}  // namespace keyturn::reconstruction::detail
