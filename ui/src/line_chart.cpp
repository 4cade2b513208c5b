#include "keyturn/ui/line_chart.h"

#include <QApplication>
#include <QGraphicsScene>
#include <QImage>
#include <QPainter>
#include <QtCharts/QChart>
#include <QtCharts/QLineSeries>
#include <QtCharts/QScatterSeries>
#include <QtCharts/QValueAxis>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "headless_app.h"
#include "keyturn/core/error.h"

namespace keyturn::ui {
void saveChartPng(const LineChart& c, const std::string& path, int width, int height) {
  ensureApplication();
  auto* chart = new QtCharts::QChart();
  chart->setTitle(QString::fromStdString(c.title));
  chart->legend()->setAlignment(Qt::AlignBottom);
  auto* ax = new QtCharts::QValueAxis();
  auto* ay = new QtCharts::QValueAxis();
  ax->setTitleText(QString::fromStdString(c.x_label));
  ay->setTitleText(QString::fromStdString(c.y_label));
  chart->addAxis(ax, Qt::AlignBottom);
  chart->addAxis(ay, Qt::AlignLeft);
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  // Colour-blind-safe palette (Okabe–Ito), so detectors stay apart in print too.
  static const QColor palette[] = {QColor(0, 114, 178), QColor(230, 159, 0), QColor(0, 158, 115),
                                   QColor(204, 121, 167), QColor(213, 94, 0), QColor(86, 180, 233),
                                   QColor(240, 228, 66), QColor(0, 0, 0)};
  int k = 0;
  for (const auto& s : c.series) {
    auto* line = new QtCharts::QLineSeries();
    line->setName(QString::fromStdString(s.name));
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      line->append(s.x[i], s.y[i]);
      xmin = std::min(xmin, s.x[i]);
      xmax = std::max(xmax, s.x[i]);
      ymin = std::min(ymin, s.y[i]);
      ymax = std::max(ymax, s.y[i]);
    }
    QPen pen(palette[k++ % 8]);
    pen.setWidth(3);
    line->setPen(pen);
    line->setPointsVisible(true);
    chart->addSeries(line);
    line->attachAxis(ax);
    line->attachAxis(ay);
  }
  if (xmin > xmax) xmin = 0, xmax = 1, ymin = 0, ymax = 1;
  if (std::isfinite(c.y_min)) ymin = c.y_min;
  if (std::isfinite(c.y_max)) ymax = c.y_max;
  if (ymax <= ymin) ymax = ymin + 1;
  if (xmax <= xmin) xmax = xmin + 1;
  ax->setRange(xmin, xmax);
  ay->setRange(ymin, ymax);
  ax->setLabelFormat("%.3g");
  ay->setLabelFormat("%.3g");

  QGraphicsScene scene;
  scene.addItem(chart);  // the scene owns the chart
  chart->setGeometry(0, 0, width, height);
  QImage img(width, height, QImage::Format_ARGB32);
  img.fill(Qt::white);
  {
    QPainter p(&img);
    p.setRenderHint(QPainter::Antialiasing);
    scene.render(&p, QRectF(0, 0, width, height), QRectF(0, 0, width, height));
  }
  const std::filesystem::path target(path);
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path());
  if (!img.save(QString::fromStdString(path), "PNG")) throw Error(path + ": cannot write the chart PNG");
}

}  // namespace keyturn::ui
