#pragma once
// A learned set function over a view's keypoints (issue 47): the network sees the "kpset" block
// (feature_cache.h) — K and the keypoints — and learns from their pairwise geometry what the PDFs
// histogram by fixed bins. Every pair (i, j) of keypoints gives five rigid-motion invariant values
// (its distance, the distance in RMS radii of the set, the two radii's sum and difference in RMS
// radii, the angle between the two at the centroid); a small shared network embeds each pair, the
// embeddings are pooled (mean and max, so the order of keypoints is irrelevant), and a head maps the
// pool, log K and the RMS radius (and any further blocks of the row, standardised) to classes.
#include "keyturn/learning/classifier.h"

namespace keyturn::learning {

// Made by the plugin "mlp" (the networks' module, with libtorch).
std::unique_ptr<Classifier> makeSetNetworkClassifier(const ClassifierParams& params);
using MakeSetNetworkClassifierFunction = Classifier*(const ClassifierParams& params);

}  // namespace keyturn::learning
