#pragma once
// ISS's weighted scatter (Tombari et al., Eq. 9) about one point over a set of neighbours stored by
// coordinate: the sum over the neighbours within r of p of w·(q − p)(q − p)ᵀ, their weight and
// count. Keypoint refinement evaluates it for every candidate against the same neighbours, so it
// is the refinement's inner loop (58 % of its time, scalar, with an unpredictable branch); the AVX2
// path masks instead of branching, four neighbours at a time, and gives the scalar sums up to the
// order of addition. Internal to keyturn_core.
#include <Eigen/Core>
#include <vector>

namespace keyturn::detail {

// Neighbours by coordinate, padded to a multiple of 4 with points of weight 0 far outside any radius.
class ScatterNeighbours {
 public:
  void clear() { x_.clear(), y_.clear(), z_.clear(), w_.clear(); }
  void add(const Eigen::Vector3d& q, double w) {
    x_.push_back(q.x()), y_.push_back(q.y()), z_.push_back(q.z()), w_.push_back(w);
  }
  void pad() {
    while (x_.size() % 4 != 0) add(Eigen::Vector3d::Constant(1e30), 0.0);
  }
  std::size_t size() const { return x_.size(); }
  const double* x() const { return x_.data(); }
  const double* y() const { return y_.data(); }
  const double* z() const { return z_.data(); }
  const double* w() const { return w_.data(); }

 private:
  std::vector<double> x_, y_, z_, w_;
};

struct WeightedScatter {
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();  // not yet divided by weight
  double weight = 0;
  int count = 0;  // neighbours within r (p itself among them when it is one)
};

// Over the padded neighbours within r (squared: r2) of p; the AVX2 path when the CPU has it.
WeightedScatter weightedScatter(const ScatterNeighbours& q, const Eigen::Vector3d& p, double r2);
WeightedScatter weightedScatterScalar(const ScatterNeighbours& q, const Eigen::Vector3d& p, double r2);

}  // namespace keyturn::detail
