#include "support/synthetic_clouds.h"

#include <cmath>
#include <set>
#include <tuple>

namespace keyturn::test {

std::vector<Eigen::Vector3f> cubeSurface(float side, int n, const Eigen::Vector3f& centre) {
  std::set<std::tuple<int, int, int>> seen;
  std::vector<Eigen::Vector3f> out;
  const float h = side / 2;
  for (int axis = 0; axis < 3; ++axis)
    for (int s = 0; s < 2; ++s)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          int g[3];
          g[axis] = s * (n - 1);
          g[(axis + 1) % 3] = a;
          g[(axis + 2) % 3] = b;
          if (!seen.insert({g[0], g[1], g[2]}).second) continue;
          Eigen::Vector3f p;
          for (int c = 0; c < 3; ++c) p[c] = -h + side * static_cast<float>(g[c]) / (n - 1);
          out.push_back(p + centre);
        }
  return out;
}

std::vector<Eigen::Vector3f> cylinderSurface(float r, float h, int around, int rings) {
  std::vector<Eigen::Vector3f> out;
  for (int k = 0; k < rings; ++k)
    for (int i = 0; i < around; ++i) {
      const float a = 2.f * static_cast<float>(M_PI) * i / around;
      out.emplace_back(r * std::cos(a), r * std::sin(a), h * k / (rings - 1));
    }
  return out;
}

Cloud organizedPlanes(int width, int height, float f, float z_back, float z_front, int u0, int u1,
                      int v0, int v1) {
  Cloud c;
  c.width = width;
  c.height = height;
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      const bool front = u >= u0 && u < u1 && v >= v0 && v < v1;
      const float z = front ? z_front : z_back;
      c.points.emplace_back((u + 0.5f - width / 2.f) / f * z, (v + 0.5f - height / 2.f) / f * z, z);
    }
  return c;
}

Cloud unorganized(const std::vector<Eigen::Vector3f>& pts) {
  Cloud c;
  c.points = pts;
  c.width = static_cast<std::uint32_t>(pts.size());
  c.height = 1;
  return c;
}

}  // namespace keyturn::test
