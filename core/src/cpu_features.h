#pragma once
// Whether this CPU runs AVX2, asked once. The AVX2 paths (graph_search.h's relaxations,
// weighted_scatter.h's scatters) are compiled with a target attribute and chosen at run time, so
// one binary runs on any x86-64. Internal to keyturn_core.
namespace keyturn::detail {

inline bool cpuHasAvx2() {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
#else
  return false;
#endif
}

}  // namespace keyturn::detail
