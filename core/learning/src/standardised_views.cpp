#include "standardised_views.h"

#include <algorithm>
#include <cmath>

namespace keyturn::learning::detail {

void fitStandardisation(const Matrix& x, std::vector<float>& mean, std::vector<float>& scale) {
  const Eigen::Index cols = x.cols();
  mean.assign(static_cast<std::size_t>(cols), 0.f);
  scale.assign(static_cast<std::size_t>(cols), 1.f);
  for (Eigen::Index k = 0; k < cols; ++k) {
    double sum = 0, sq = 0;
    int n = 0;
    for (Eigen::Index r = 0; r < x.rows(); ++r)
      if (std::isfinite(x(r, k))) sum += x(r, k), sq += static_cast<double>(x(r, k)) * x(r, k), ++n;
    const double m = n ? sum / n : 0.0;
    const double sd = n ? std::sqrt(std::max(0.0, sq / n - m * m)) : 0.0;
    mean[static_cast<std::size_t>(k)] = static_cast<float>(m);
    scale[static_cast<std::size_t>(k)] = sd > 1e-9 ? static_cast<float>(sd) : 1.f;  // a constant column adds nothing
  }
}

Matrix standardisedRows(const Matrix& x, const std::vector<float>& mean, const std::vector<float>& scale) {
  Matrix out(x.rows(), x.cols());
  for (Eigen::Index r = 0; r < x.rows(); ++r)
    for (Eigen::Index k = 0; k < x.cols(); ++k) {
      const auto kk = static_cast<std::size_t>(k);
      out(r, k) = std::isfinite(x(r, k)) ? (x(r, k) - mean[kk]) / scale[kk] : 0.f;
    }
  return out;
}

Eigen::RowVectorXf standardisedRow(const Eigen::RowVectorXf& x, const std::vector<float>& mean,
                                   const std::vector<float>& scale) {
  Eigen::RowVectorXf v(x.size());
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    const auto kk = static_cast<std::size_t>(k);
    v(k) = std::isfinite(x(k)) ? (x(k) - mean[kk]) / scale[kk] : 0.f;
  }
  return v;
}

double rmsDistance(const Eigen::RowVectorXf& a, const Eigen::RowVectorXf& b) {
  return std::sqrt(static_cast<double>((a - b).squaredNorm()) / static_cast<double>(std::max<Eigen::Index>(1, a.size())));
}

}  // namespace keyturn::learning::detail
