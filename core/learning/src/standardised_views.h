#pragma once
// Training views standardised, the space in which the knn open-set scores (open_set.h) and pose
// fusion's evidence (view_fusion.h) measure how far a view lies from the training views: each
// feature less the training views' mean over their spread, a missing value at the mean.
#include <vector>

#include "keyturn/learning/classifier.h"

namespace keyturn::learning::detail {

// Per column of x, the mean and spread of its finite values (a constant or empty column: 1).
void fitStandardisation(const Matrix& x, std::vector<float>& mean, std::vector<float>& scale);
Matrix standardisedRows(const Matrix& x, const std::vector<float>& mean, const std::vector<float>& scale);
Eigen::RowVectorXf standardisedRow(const Eigen::RowVectorXf& x, const std::vector<float>& mean,
                                   const std::vector<float>& scale);
// The RMS per-feature distance between two standardised rows.
double rmsDistance(const Eigen::RowVectorXf& a, const Eigen::RowVectorXf& b);

}  // namespace keyturn::learning::detail
