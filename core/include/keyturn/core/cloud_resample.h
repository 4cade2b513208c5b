#pragma once
// Smaller inputs cut from a real frame, for measuring how the chain's cost grows
// with input size (`keyturn bench --scaling`): the same scene seen by a sensor of
// fewer pixels, or fewer points of one segmented object.
#include <cstddef>

#include "keyturn/core/cloud.h"

namespace keyturn {

// The organized `frame` as a sensor of about `pixels` pixels with the same field of
// view and aspect would see it: a w × h grid (w/h kept to the frame's, w·h ≈ pixels)
// whose every pixel is the nearest source pixel's measurement — never an average,
// which would invent points across depth edges. The frame itself when pixels ≥ its
// size. Throws keyturn::Error for an unorganized cloud or pixels = 0.
Cloud resampleOrganized(const Cloud& frame, std::size_t pixels);

// `count` of the cloud's valid points drawn uniformly without replacement (seeded:
// the same cloud, count and seed give the same points, in source order), as an
// unorganized cloud. Throws keyturn::Error when the cloud has fewer valid points.
Cloud randomSubset(const Cloud& cloud, std::size_t count, unsigned long long seed);

}  // namespace keyturn
