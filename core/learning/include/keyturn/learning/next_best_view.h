#pragma once
// Next best view (issue 34, docs/results.md "Next best view"): with the turntable under keyturn's
// control, the turn whose view is expected to leave the least uncertainty about the class.
// - How the classifier behaves at each angle, from the training views: for class c seen at
//   azimuth bin b, the mean class probabilities the classifier gave held-out training views of c
//   near b — a soft confusion table L(j | c, b) (fitViewLikelihoods; evaluate's protocol fills it
//   by inner cross-validation on each fold's training views).
// - The current belief over (class c, rotation φ): pose fusion's joint belief (FusionState), φ the
//   training views' azimuth bin of the sequence's first view.
// - For a turn δ from the first view, the next view's answer j is predicted as
//   P(j) = Σ_{c,φ} P(c, φ) L(j | c, φ + δ), the class belief after it as
//   P(c | j) ∝ Σ_φ P(c, φ) L(j | c, φ + δ), and the turn chosen is the one with the lowest expected
//   entropy Σ_j P(j) H(P(· | j)) among the turns not yet taken.
#include <vector>

#include "keyturn/learning/classifier.h"

namespace keyturn::learning {

struct ViewLikelihoods {
  int classes = 0;
  int bins = 72;  // 360° / bin width
  std::vector<double> table;  // [(c * bins + b) * classes + j]: L(j | c, b), each (c, b) summing to 1
  double at(int c, int b, int j) const {
    return table[(static_cast<std::size_t>(c) * static_cast<std::size_t>(bins) + static_cast<std::size_t>(b)) *
                     static_cast<std::size_t>(classes) + static_cast<std::size_t>(j)];
  }
};

struct ViewLikelihoodOptions {
  double bin_deg = 5;      // the azimuth bins (as pose fusion's)
  double window_deg = 15;  // a bin averages the views of its class within half this of its centre
  double prior = 0.05;     // weight of an even spread over the classes, against the views' mean
};

// probabilities: the class probabilities given to views (rows) that the classifier did not train
// on; truth and azimuth_deg one per row. A (class, bin) without a view in its window takes its
// class's mean over all its views; a class without any view, an even spread. Throws
// keyturn::Error for mismatched sizes, a class index out of range, or a bin width that does not
// divide the turn into 4 or more bins.
ViewLikelihoods fitViewLikelihoods(const Matrix& probabilities, const std::vector<int>& truth,
                                   const std::vector<double>& azimuth_deg, int classes,
                                   const ViewLikelihoodOptions& options = {});

// Entropy (nats) of a distribution.
double entropyOf(const std::vector<double>& p);

// The expected entropy of the class belief after one more view, `turn_deg` from the sequence's
// first view, given the joint belief [c][φ] (FusionState::jointBelief). Throws keyturn::Error
// when the belief's shape is not the table's (classes × bins).
double expectedEntropyAfter(const ViewLikelihoods& likelihoods, const std::vector<std::vector<double>>& joint,
                            double turn_deg);

struct NextView {
  double turn_deg = 0;          // from the sequence's first view
  double expected_entropy = 0;  // after the view at that turn
};

// Among `candidates_deg` (turns from the first view the turntable can reach) those not within
// half a bin of one in `taken_deg`, the one with the lowest expected entropy (the first listed on
// a tie). Throws keyturn::Error when no candidate is left.
NextView chooseNextView(const ViewLikelihoods& likelihoods, const std::vector<std::vector<double>>& joint,
                        const std::vector<double>& candidates_deg, const std::vector<double>& taken_deg);

}  // namespace keyturn::learning
