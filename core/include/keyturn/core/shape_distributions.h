#pragma once
// Osada et al.'s shape distributions, the paper's baseline: shape functions of
// random surface samples (here: random points of the filtered view), seedable.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace keyturn {

struct OsadaOptions {
  int samples = 20000;       // shape-function evaluations per distribution
  std::uint64_t seed = 7;
};

enum class OsadaFunction { D1, D2, D3, D4, A3 };

// D1: distance of a random point to the centroid; D2: distance of two random
// points; D3: sqrt area of three; D4: cube root of the tetrahedron volume of four;
// A3: angle at the middle point of three (radians). Degenerate draws are skipped.
std::vector<float> osadaShapeFunction(const std::vector<Eigen::Vector3f>& points, OsadaFunction f,
                                      const OsadaOptions& options);

}  // namespace keyturn
