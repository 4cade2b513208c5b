#include "weighted_scatter.h"

#include "cpu_features.h"
#include "keyturn/core/keypoint_refinement.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define KEYTURN_SCATTER_AVX2 1
#endif

namespace keyturn::detail {
namespace {

bool g_scalar_scatter = false;  // useScalarScatter

WeightedScatter fromSums(double xx, double xy, double xz, double yy, double yz, double zz, double w, int count) {
  WeightedScatter s;
  s.scatter << xx, xy, xz, xy, yy, yz, xz, yz, zz;
  s.weight = w, s.count = count;
  return s;
}

#ifdef KEYTURN_SCATTER_AVX2
__attribute__((target("avx2"))) double lanesSum(__m256d v) {
  alignas(32) double a[4];
  _mm256_store_pd(a, v);
  return (a[0] + a[1]) + (a[2] + a[3]);
}

__attribute__((target("avx2"))) WeightedScatter scatterAvx2(const ScatterNeighbours& q, const Eigen::Vector3d& p,
                                                             double r2) {
  const __m256d px = _mm256_set1_pd(p.x()), py = _mm256_set1_pd(p.y()), pz = _mm256_set1_pd(p.z());
  const __m256d limit = _mm256_set1_pd(r2), one = _mm256_set1_pd(1.0);
  __m256d xx = _mm256_setzero_pd(), xy = xx, xz = xx, yy = xx, yz = xx, zz = xx, ws = xx, count = xx;
  for (std::size_t i = 0; i < q.size(); i += 4) {
    const __m256d dx = _mm256_sub_pd(_mm256_loadu_pd(q.x() + i), px);
    const __m256d dy = _mm256_sub_pd(_mm256_loadu_pd(q.y() + i), py);
    const __m256d dz = _mm256_sub_pd(_mm256_loadu_pd(q.z() + i), pz);
    const __m256d d2 =
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz));
    const __m256d inside = _mm256_cmp_pd(d2, limit, _CMP_LT_OQ);
    const __m256d w = _mm256_and_pd(_mm256_loadu_pd(q.w() + i), inside);
    const __m256d wx = _mm256_mul_pd(w, dx), wy = _mm256_mul_pd(w, dy), wz = _mm256_mul_pd(w, dz);
    xx = _mm256_add_pd(xx, _mm256_mul_pd(wx, dx)), xy = _mm256_add_pd(xy, _mm256_mul_pd(wx, dy));
    xz = _mm256_add_pd(xz, _mm256_mul_pd(wx, dz)), yy = _mm256_add_pd(yy, _mm256_mul_pd(wy, dy));
    yz = _mm256_add_pd(yz, _mm256_mul_pd(wy, dz)), zz = _mm256_add_pd(zz, _mm256_mul_pd(wz, dz));
    ws = _mm256_add_pd(ws, w), count = _mm256_add_pd(count, _mm256_and_pd(one, inside));
  }
  return fromSums(lanesSum(xx), lanesSum(xy), lanesSum(xz), lanesSum(yy), lanesSum(yz), lanesSum(zz), lanesSum(ws),
                  static_cast<int>(lanesSum(count)));
}
#endif

}  // namespace

WeightedScatter weightedScatterScalar(const ScatterNeighbours& q, const Eigen::Vector3d& p, double r2) {
  double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0, ws = 0;
  int count = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    const double dx = q.x()[i] - p.x(), dy = q.y()[i] - p.y(), dz = q.z()[i] - p.z();
    if (dx * dx + dy * dy + dz * dz >= r2) continue;
    const double w = q.w()[i];
    xx += w * dx * dx, xy += w * dx * dy, xz += w * dx * dz;
    yy += w * dy * dy, yz += w * dy * dz, zz += w * dz * dz;
    ws += w, ++count;
  }
  return fromSums(xx, xy, xz, yy, yz, zz, ws, count);
}

void useScalarScatter(bool scalar) { g_scalar_scatter = scalar; }

bool scatterUsesAvx2() {
#ifdef KEYTURN_SCATTER_AVX2
  return cpuHasAvx2() && !g_scalar_scatter;
#else
  return false;
#endif
}

WeightedScatter weightedScatter(const ScatterNeighbours& q, const Eigen::Vector3d& p, double r2) {
#ifdef KEYTURN_SCATTER_AVX2
  if (scatterUsesAvx2()) return scatterAvx2(q, p, r2);
#endif
  return weightedScatterScalar(q, p, r2);
}

}  // namespace keyturn::detail
