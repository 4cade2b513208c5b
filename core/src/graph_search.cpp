#include "graph_search.h"

namespace keyturn {
namespace {
bool g_scalar_geodesics = false;  // detail::useScalarGeodesics
}  // namespace

bool detail::useAvx2() {
#ifdef KEYTURN_GEODESIC_AVX2
  static const bool has = __builtin_cpu_supports("avx2");
  return has && !g_scalar_geodesics;
#else
  return false;
#endif
}

void detail::useScalarGeodesics(bool scalar) { g_scalar_geodesics = scalar; }
bool detail::geodesicsUseAvx2() { return useAvx2(); }

}  // namespace keyturn
