#include "image_panel.h"

#include <QPainter>
#include <algorithm>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace keyturn::studio {
namespace {

// The value at fraction q of the sorted non-zero samples (0 = no return).
double percentile(std::vector<std::uint16_t> v, double q) {
  v.erase(std::remove(v.begin(), v.end(), 0), v.end());
  if (v.empty()) return 0;
  const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[static_cast<std::size_t>(k)];
}

QImage fromMat(const cv::Mat& bgr) {
  QImage img(bgr.cols, bgr.rows, QImage::Format_RGB888);
  for (int y = 0; y < bgr.rows; ++y) {
    const auto* src = bgr.ptr<cv::Vec3b>(y);
    uchar* dst = img.scanLine(y);
    for (int x = 0; x < bgr.cols; ++x) {
      dst[3 * x] = src[x][2];
      dst[3 * x + 1] = src[x][1];
      dst[3 * x + 2] = src[x][0];
    }
  }
  return img;
}

// 16-bit → 8-bit between lo and hi; 0 (no return) stays 0.
cv::Mat to8(const std::vector<std::uint16_t>& raw, int w, int h, double lo, double hi, bool keep_zero_black) {
  cv::Mat out(h, w, CV_8UC1);
  const double span = std::max(1.0, hi - lo);
  for (int i = 0; i < w * h; ++i) {
    const std::uint16_t r = raw[static_cast<std::size_t>(i)];
    const double t = std::clamp((r - lo) / span, 0.0, 1.0);
    out.data[i] = (keep_zero_black && r == 0) ? 0 : static_cast<uchar>(1 + 254 * t);
  }
  return out;
}

}  // namespace

QImage distanceImage(const std::vector<std::uint16_t>& raw, int w, int h, double metres_per_count, ImageScale* scale) {
  if (raw.size() != static_cast<std::size_t>(w) * static_cast<std::size_t>(h) || w <= 0) return {};
  const double lo = percentile(raw, 0.02), hi = std::max(lo + 1, percentile(raw, 0.98));
  cv::Mat grey = to8(raw, w, h, lo, hi, true), colour;
  cv::applyColorMap(grey, colour, cv::COLORMAP_TURBO);
  for (int i = 0; i < w * h; ++i)
    if (raw[static_cast<std::size_t>(i)] == 0) colour.at<cv::Vec3b>(i / w, i % w) = cv::Vec3b(0, 0, 0);
  if (scale) *scale = {lo * metres_per_count, hi * metres_per_count, "m"};
  return fromMat(colour);
}

QImage greyImage(const std::vector<std::uint16_t>& raw, int w, int h, ImageScale* scale, bool auto_level) {
  if (raw.size() != static_cast<std::size_t>(w) * static_cast<std::size_t>(h) || w <= 0) return {};
  const double hi = auto_level ? std::max(1.0, percentile(raw, 0.99)) : 65535.0;
  cv::Mat grey = to8(raw, w, h, 0, hi, false), bgr;
  cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
  if (scale) *scale = {0, hi, ""};
  return fromMat(bgr);
}

QImage colourBar(int width, int height) {
  cv::Mat ramp(height, width, CV_8UC1), colour;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) ramp.at<uchar>(y, x) = static_cast<uchar>(1 + 254 * x / std::max(1, width - 1));
  cv::applyColorMap(ramp, colour, cv::COLORMAP_TURBO);
  return fromMat(colour);
}

ImagePanel::ImagePanel(const QString& title, bool colour_bar, QWidget* parent)
    : QWidget(parent), title_(title), colour_bar_(colour_bar) {
  setMinimumSize(180, 170);
  if (colour_bar_) bar_ = colourBar(256, 1);
}

QImage rgbImage(const std::vector<std::uint8_t>& rgb, int w, int h) {
  if (w <= 0 || h <= 0 || rgb.size() != static_cast<std::size_t>(w) * h * 3) return {};
  return QImage(rgb.data(), w, h, w * 3, QImage::Format_RGB888).copy();
}

void ImagePanel::setTitle(const QString& title) {
  if (title == title_) return;
  title_ = title;
  setToolTip(title);
  update();
}

void ImagePanel::setPlaceholder(const QString& text) {
  if (text == placeholder_) return;
  placeholder_ = text;
  update();
}

void ImagePanel::setImage(const QImage& image, const ImageScale& scale) {
  image_ = image;
  scale_ = scale;
  update();
}

void ImagePanel::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.fillRect(rect(), palette().window());
  const int title_h = fontMetrics().height() + 4;
  const int bar_h = colour_bar_ ? 12 + fontMetrics().height() + 4 : 0;
  p.setPen(palette().windowText().color());
  QFont bold = font();
  bold.setBold(true);
  p.setFont(bold);
  // A title wider than the panel ends in "…" (the whole of it is the tooltip) instead of running
  // into the next panel's.
  const int gap = QFontMetrics(bold).horizontalAdvance(' ');
  p.drawText(QRect(0, 0, width() - gap, title_h), Qt::AlignLeft | Qt::AlignVCenter,
             QFontMetrics(bold).elidedText(title_, Qt::ElideRight, width() - gap));
  p.setFont(font());
  const QRect area(0, title_h, width(), height() - title_h - bar_h);
  if (image_.isNull()) {
    p.fillRect(area, QColor(32, 32, 32));
    p.setPen(QColor(160, 160, 160));
    p.drawText(area, Qt::AlignCenter, placeholder_.isEmpty() ? tr("no camera") : placeholder_);
    return;
  }
  const QSize s = image_.size().scaled(area.size(), Qt::KeepAspectRatio);
  const QRect target(area.x() + (area.width() - s.width()) / 2, area.y(), s.width(), s.height());
  p.drawImage(target, image_);
  if (colour_bar_) {
    const QRect bar(target.x(), target.bottom() + 4, target.width(), 10);
    p.drawImage(bar, bar_);
    p.setPen(palette().windowText().color());
    const QRect labels(bar.x(), bar.bottom() + 2, bar.width(), fontMetrics().height());
    p.drawText(labels, Qt::AlignLeft, QString("%1 %2").arg(scale_.lo, 0, 'f', 2).arg(scale_.unit));
    p.drawText(labels, Qt::AlignRight, QString("%1 %2").arg(scale_.hi, 0, 'f', 2).arg(scale_.unit));
  }
}

}  // namespace keyturn::studio
