// A view as a depth frame for TSDF integration (surface.h): the pinhole its grid lies on, fitted
// from the frame as read, and the filtered view drawn through it.
#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "keyturn/reconstruction/surface.h"

namespace keyturn::reconstruction {

namespace {

// Least squares pixel = f · ratio + c over the pixels; the rms miss in pixels.
struct AxisFit {
  double f = 0, c = 0, rms_px = 0;
};

AxisFit fitAxis(const std::vector<double>& ratio, const std::vector<double>& pixel) {
  Eigen::Matrix2d ata = Eigen::Matrix2d::Zero();
  Eigen::Vector2d atb = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < ratio.size(); ++i) {
    const Eigen::Vector2d a(ratio[i], 1.0);
    ata += a * a.transpose(), atb += a * pixel[i];
  }
  AxisFit fit;
  if (std::abs(ata.determinant()) < 1e-12 * ata.trace() * ata.trace()) return fit;  // one column: no fit
  const Eigen::Vector2d fc = ata.ldlt().solve(atb);
  fit.f = fc[0], fit.c = fc[1];
  double sum = 0;
  for (std::size_t i = 0; i < ratio.size(); ++i) sum += std::pow(fit.f * ratio[i] + fit.c - pixel[i], 2);
  fit.rms_px = std::sqrt(sum / double(ratio.size()));
  return fit;
}

std::optional<DepthFrame> refuse(std::string* why, const std::string& reason) {
  if (why) *why = reason;
  return std::nullopt;
}

}  // namespace

std::optional<DepthFrame> depthFrameFromCloud(const Cloud& as_read, const Cloud& filtered,
                                              const Eigen::Matrix4d& world_from_view, std::string* why) {
  if (!as_read.organized() || as_read.width * as_read.height != as_read.size())
    return refuse(why, "not an organized depth frame (" + std::to_string(as_read.width) + " × " +
                           std::to_string(as_read.height) + ")");
  std::vector<double> xz, u, yz, v;
  for (std::size_t i = 0; i < as_read.size(); ++i) {
    const auto& p = as_read.points[i];
    if (!Cloud::isValid(p) || p.z() <= 0) continue;
    xz.push_back(p.x() / p.z()), u.push_back(double(i % as_read.width));
    yz.push_back(p.y() / p.z()), v.push_back(double(i / as_read.width));
  }
  if (xz.size() < 100)
    return refuse(why, std::to_string(xz.size()) + " points in front of the camera, a depth frame needs 100");
  const AxisFit fu = fitAxis(xz, u), fv = fitAxis(yz, v);
  if (fu.f <= 0 || fv.f <= 0)
    return refuse(why, "its points do not lie on a camera's rays (no positive focal length fits its grid)");
  const double rms = std::hypot(fu.rms_px, fv.rms_px);
  if (rms > 1.0) {
    std::string text = "its points miss the best pinhole's pixels by ";
    text += std::to_string(rms).substr(0, 4) + " px rms (a lens model keyturn does not fit)";
    return refuse(why, text);
  }
  DepthFrame f;
  f.width = int(as_read.width), f.height = int(as_read.height);
  f.fx = fu.f, f.cx = fu.c, f.fy = fv.f, f.cy = fv.c, f.fit_rms_px = rms;
  f.world_from_view = world_from_view;
  f.depth_m.assign(std::size_t(f.width) * std::size_t(f.height), 0.f);
  for (const auto& p : filtered.points) {
    if (!Cloud::isValid(p) || p.z() <= 0) continue;
    const long col = std::lround(f.fx * p.x() / p.z() + f.cx), row = std::lround(f.fy * p.y() / p.z() + f.cy);
    if (col < 0 || row < 0 || col >= f.width || row >= f.height) continue;
    float& d = f.depth_m[std::size_t(row) * std::size_t(f.width) + std::size_t(col)];
    if (d == 0.f || p.z() < d) d = p.z();
  }
  return f;
}

}  // namespace keyturn::reconstruction
