#include "graph_search.h"

#include "cpu_features.h"

namespace keyturn {
namespace {
bool g_scalar_geodesics = false;  // detail::useScalarGeodesics
}  // namespace

bool detail::useAvx2() {
#ifdef KEYTURN_GEODESIC_AVX2
  return cpuHasAvx2() && !g_scalar_geodesics;
#else
  return false;
#endif
}

void detail::useScalarGeodesics(bool scalar) { g_scalar_geodesics = scalar; }
bool detail::geodesicsUseAvx2() { return useAvx2(); }

}  // namespace keyturn
