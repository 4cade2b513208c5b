#pragma once
// Analytic point sets with known geometry for unit tests.
#include <Eigen/Core>
#include <vector>

#include "keyturn/core/cloud.h"

namespace keyturn::test {

// Surface of an axis-aligned cube of side `side` centred at `centre`, sampled
// on a regular grid of `n` × `n` points per face (shared edges deduplicated).
std::vector<Eigen::Vector3f> cubeSurface(float side, int n, const Eigen::Vector3f& centre);

// Side surface of a cylinder (axis z) of radius r and height h, sampled with
// `around` points per ring and `rings` rings.
std::vector<Eigen::Vector3f> cylinderSurface(float r, float h, int around, int rings);

// An organized pinhole view (width × height, focal f px) of a fronto-parallel
// plane at depth z, optionally with a second, nearer rectangle in front of it.
Cloud organizedPlanes(int width, int height, float f, float z_back, float z_front,
                      int front_u0, int front_u1, int front_v0, int front_v1);

Cloud unorganized(const std::vector<Eigen::Vector3f>& pts);

}  // namespace keyturn::test
