#pragma once
// One live camera image (distance, amplitude or confidence) scaled to its panel,
// with a colour scale for the distance image.
#include <QImage>
#include <QWidget>
#include <cstdint>
#include <vector>

namespace keyturn::studio {

struct ImageScale {
  double lo = 0, hi = 1;   // what the colour scale's ends stand for
  QString unit;            // "m" for distance; empty for unitless images
};

// Raw 16-bit camera images → displayable images. `metres_per_count` turns raw
// distance into metres; the colour range is the valid pixels' 2nd–98th percentile.
QImage distanceImage(const std::vector<std::uint16_t>& raw, int w, int h, double metres_per_count, ImageScale* scale);
// auto_level: 0 … the 99th percentile (amplitude); otherwise the full 16-bit range (confidence).
QImage greyImage(const std::vector<std::uint16_t>& raw, int w, int h, ImageScale* scale, bool auto_level = true);
QImage colourBar(int width, int height);
// A depth camera's RGB888 colour image (copied); null when the size does not match the bytes.
QImage rgbImage(const std::vector<std::uint8_t>& rgb, int w, int h);  // the distance colour map, low → high, left → right

class ImagePanel : public QWidget {
  Q_OBJECT
 public:
  ImagePanel(const QString& title, bool colour_bar, QWidget* parent = nullptr);
  void setImage(const QImage& image, const ImageScale& scale);
  void setTitle(const QString& title);  // the panels say what a depth camera's images are
  // What the panel says while it has no image ("no camera" until a camera says otherwise).
  void setPlaceholder(const QString& text);
  const QImage& image() const { return image_; }
  QSize sizeHint() const override { return {300, 260}; }

 protected:
  void paintEvent(QPaintEvent*) override;

 private:
  QString title_;
  QString placeholder_;
  bool colour_bar_;
  QImage image_, bar_;
  ImageScale scale_;
};

}  // namespace keyturn::studio
