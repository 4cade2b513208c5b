#include "confusion_plot_png.h"

#include <QFont>
#include <QFontMetrics>
#include <QImage>
#include <QPainter>
#include <algorithm>

#include "headless_app.h"
#include "keyturn/core/error.h"

namespace keyturn::plots {

void saveConfusionPng(const ConfusionPlot& m, const std::string& path) {
  ensureApplication();
  const int n = static_cast<int>(m.labels.size());
  if (n == 0 || static_cast<int>(m.counts.size()) != n) throw Error(path + ": a confusion matrix needs its labels");
  QFont font("DejaVu Sans", 9);
  const QFontMetrics fm(font);
  int label_w = 0;
  for (const auto& l : m.labels) label_w = std::max(label_w, fm.horizontalAdvance(QString::fromStdString(l)));
  const int cell = std::max(28, fm.horizontalAdvance("0000") + 8);
  const int left = label_w + 40, top = label_w + 60, size = cell * n;
  QImage img(left + size + 30, top + size + 50, QImage::Format_RGB32);
  img.fill(Qt::white);
  QPainter p(&img);
  p.setRenderHint(QPainter::Antialiasing);
  p.setFont(QFont("DejaVu Sans", 11, QFont::Bold));
  p.drawText(QRect(0, 6, img.width(), 24), Qt::AlignCenter, QString::fromStdString(m.title));
  p.setFont(font);
  for (int r = 0; r < n; ++r) {
    int total = 0;
    for (int c = 0; c < n; ++c) total += m.counts[r].at(static_cast<std::size_t>(c));
    for (int c = 0; c < n; ++c) {
      const int v = m.counts[r][static_cast<std::size_t>(c)];
      const double share = total ? static_cast<double>(v) / total : 0.0;
      // White → blue (Okabe–Ito blue 0,114,178) by the share of the true class.
      const QColor shade(static_cast<int>(255 - share * 255), static_cast<int>(255 - share * 141),
                         static_cast<int>(255 - share * 77));
      const QRect box(left + c * cell, top + r * cell, cell, cell);
      p.fillRect(box, shade);
      p.setPen(QColor(220, 220, 220));
      p.drawRect(box);
      if (v) {
        p.setPen(share > 0.5 ? Qt::white : Qt::black);
        p.drawText(box, Qt::AlignCenter, QString::number(v));
      }
    }
    p.setPen(Qt::black);
    p.drawText(QRect(0, top + r * cell, left - 6, cell), Qt::AlignRight | Qt::AlignVCenter,
               QString::fromStdString(m.labels[static_cast<std::size_t>(r)]));
  }
  for (int c = 0; c < n; ++c) {
    p.save();
    p.translate(left + c * cell + cell / 2 + fm.height() / 3, top - 6);
    p.rotate(-90);
    p.drawText(0, 0, QString::fromStdString(m.labels[static_cast<std::size_t>(c)]));
    p.restore();
  }
  p.drawText(QRect(left, top + size + 8, size, 20), Qt::AlignCenter, "predicted");
  p.save();
  p.translate(14, top + size / 2 + 20);
  p.rotate(-90);
  p.drawText(0, 0, "true");
  p.restore();
  p.end();
  if (!img.save(QString::fromStdString(path), "PNG")) throw Error(path + ": cannot write the PNG");
}

}  // namespace keyturn::plots
