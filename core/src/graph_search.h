#pragma once
// The graph search of the local complete graph (geodesic.h): an indexed 4-ary heap of vertices and
// Dijkstra over the graph's CSR arrays, with an AVX2 path for the relaxations that gives the scalar
// loop's exact results. Internal to keyturn_core: geodesic.cpp's searches run it.
#include <algorithm>
#include <limits>
#include <vector>

#include "keyturn/core/geodesic.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define KEYTURN_GEODESIC_AVX2 1
#endif

namespace keyturn::detail {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Whether the relaxations take the AVX2 path: the CPU has it and useScalarGeodesics did not turn it off.
bool useAvx2();

// Indexed 4-ary min-heap of vertices keyed by cost: at most one entry per
// vertex (decrease-key instead of duplicates), so it never outgrows the graph.
class VertexHeap {
 public:
  explicit VertexHeap(std::size_t n) : pos_(n, -1) { heap_.reserve(n); }
  bool empty() const { return heap_.empty(); }
  void clear() {
    for (int v : heap_) pos_[v] = -1;
    heap_.clear();
  }
  void pushOrDecrease(int v, const float* key) {
    int i = pos_[v];
    if (i < 0) {
      i = static_cast<int>(heap_.size());
      heap_.push_back(v);
    }
    siftUp(i, v, key);
  }
  int pop(const float* key) {
    const int top = heap_[0];
    pos_[top] = -1;
    const int last = heap_.back();
    heap_.pop_back();
    if (!heap_.empty()) siftDown(last, key);
    return top;
  }

 private:
  void siftUp(int i, int v, const float* key) {
    const float k = key[v];
    while (i > 0) {
      const int parent = (i - 1) >> 2;
      const int pv = heap_[parent];
      if (key[pv] <= k) break;
      heap_[i] = pv;
      pos_[pv] = i;
      i = parent;
    }
    heap_[i] = v;
    pos_[v] = i;
  }
  void siftDown(int v, const float* key) {
    const int n = static_cast<int>(heap_.size());
    const float k = key[v];
    int i = 0;
    for (;;) {
      const int first = 4 * i + 1;
      if (first >= n) break;
      int best = first;
      float bk = key[heap_[first]];
      const int last = std::min(first + 4, n);
      for (int c = first + 1; c < last; ++c) {
        const float ck = key[heap_[c]];
        if (ck < bk) {
          bk = ck;
          best = c;
        }
      }
      if (bk >= k) break;
      heap_[i] = heap_[best];
      pos_[heap_[i]] = i;
      i = best;
    }
    heap_[i] = v;
    pos_[v] = i;
  }
  std::vector<int> heap_;
  std::vector<int> pos_;
};

// Dijkstra over the CSR graph. Cost is the Euclidean length or the curvature-
// weighted cost; for the latter `euclid` carries the Euclidean length of the
// path that minimises the cost. Stops once `remaining` targets have settled.
class Dijkstra {
 public:
  explicit Dijkstra(const LocalCompleteGraph& g)
      : g_(g), cost_(g.vertexCount(), kInf), euclid_(g.vertexCount(), kInf),
        settled_(g.vertexCount(), 0), heap_(g.vertexCount()) {}

  template <typename OnSettle>
  void run(int source, bool curved, int remaining, OnSettle&& on_settle) {
    if (curved) runImpl<true>(source, remaining, on_settle);
    else runImpl<false>(source, remaining, on_settle);
  }

 private:
  template <bool Curved, typename OnSettle>
  void runImpl(int source, int remaining, OnSettle& on_settle) {
    for (int v : touched_) {
      cost_[v] = kInf;
      if (Curved) euclid_[v] = kInf;
      settled_[v] = 0;
    }
    touched_.clear();
    heap_.clear();
    const int* off = Curved ? g_.curved_offsets.data() : g_.offsets.data();
    float* cost = cost_.data();
    const bool avx2 = useAvx2();
    cost[source] = 0.f;
    if (Curved) euclid_[source] = 0.f;
    touched_.push_back(source);
    heap_.pushOrDecrease(source, cost);
    while (!heap_.empty()) {
      const int v = heap_.pop(cost);
      settled_[v] = 1;
      if (on_settle(v, Curved ? euclid_[v] : cost[v]) && --remaining <= 0) return;
#ifdef KEYTURN_GEODESIC_AVX2
      if (avx2) {
        relaxAvx2<Curved>(v, off[v], off[v + 1]);
        continue;
      }
#endif
      for (int e = off[v], end = off[v + 1]; e < end; ++e) relax<Curved>(v, e);
    }
  }

  // Relaxes edge e of the settled vertex v.
  template <bool Curved>
  void relax(int v, int e) {
    const float* w = Curved ? g_.curved_cost.data() : g_.length.data();
    const int t = (Curved ? g_.curved_targets : g_.targets)[e];
    const float nc = cost_[v] + w[e];
    if (nc < cost_[t]) {
      if (settled_[t]) return;  // rounding only: settled costs are final
      if (cost_[t] == kInf) touched_.push_back(t);
      cost_[t] = nc;
      if (Curved) euclid_[t] = euclid_[v] + g_.curved_length[e];
      heap_.pushOrDecrease(t, cost_.data());
    }
  }

#ifdef KEYTURN_GEODESIC_AVX2
  // Most relaxations improve nothing (about 95 % for plain lengths, 80 % for curved costs), so eight
  // edges are compared at once — one gather of their targets' costs — and only the lanes that improve
  // go, in edge order, through the same relax(): the same float operations in the same order as the
  // scalar loop, so both give bit-identical results (tested). relax() compares again with the current
  // cost, and costs only fall, so a lane the block's compare passes over the scalar loop would too.
  template <bool Curved>
  __attribute__((target("avx2"))) void relaxAvx2(int v, int begin, int end) {
    const float* w = Curved ? g_.curved_cost.data() : g_.length.data();
    const int* tgt = Curved ? g_.curved_targets.data() : g_.targets.data();
    const float* cost = cost_.data();
    const __m256 c = _mm256_set1_ps(cost_[v]);
    int e = begin;
    for (; e + 8 <= end; e += 8) {
      const __m256i t = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(tgt + e));
      const __m256 nc = _mm256_add_ps(c, _mm256_loadu_ps(w + e));
      const __m256 old = _mm256_i32gather_ps(cost, t, 4);
      unsigned lanes = static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(nc, old, _CMP_LT_OQ)));
      while (lanes) {
        relax<Curved>(v, e + __builtin_ctz(lanes));
        lanes &= lanes - 1;
      }
    }
    for (; e < end; ++e) relax<Curved>(v, e);
  }
#endif

  const LocalCompleteGraph& g_;
  std::vector<float> cost_, euclid_;
  std::vector<char> settled_;
  VertexHeap heap_;
  std::vector<int> touched_;
};

}  // namespace keyturn::detail
