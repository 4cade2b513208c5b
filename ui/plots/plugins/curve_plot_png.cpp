#include "curve_plot_png.h"

#include <QApplication>
#include <QGraphicsScene>
#include <QGraphicsSimpleTextItem>
#include <QGraphicsTextItem>
#include <QImage>
#include <QPainter>
#include <QtCharts/QCategoryAxis>
#include <QtCharts/QChart>
#include <QtCharts/QLineSeries>
#include <QtCharts/QLogValueAxis>
#include <QtCharts/QScatterSeries>
#include <QtCharts/QValueAxis>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "headless_app.h"
#include "keyturn/core/error.h"

namespace keyturn::plots {
namespace {
QtCharts::QAbstractAxis* makeAxis(bool log, const std::string& title) {
  QtCharts::QAbstractAxis* axis;
  if (log) {
    auto* a = new QtCharts::QLogValueAxis();
    a->setBase(10.0);
    a->setMinorTickCount(8);  // 2…9 between decades
    a->setLabelFormat("%.10g");  // 1000000, not 1e+06
    axis = a;
  } else {
    auto* a = new QtCharts::QValueAxis();
    a->setLabelFormat("%.3g");
    axis = a;
  }
  axis->setTitleText(QString::fromStdString(title));
  return axis;
}

// A log axis spans whole decades so its ticks fall on 1, 10, 100…
void setRange(QtCharts::QAbstractAxis* axis, bool log, double lo, double hi) {
  if (log) {
    if (lo <= 0) lo = hi / 1000;  // a caller's y_min of 0 has no place on a log axis
    lo = std::pow(10.0, std::floor(std::log10(lo)));
    hi = std::pow(10.0, std::ceil(std::log10(hi)));
    if (hi <= lo) hi = lo * 10;
  }
  axis->setRange(lo, hi);
}

// Lays the chart out at its size and draws it; `text` (when asked) gets every text item Qt Charts
// placed, as drawn (a label given too little room is elided there, not in the plot's data).
QImage drawCurve(const CurvePlot& c, std::vector<std::string>* text) {
  const int width = c.width, height = c.height;
  ensureApplication();
  auto* chart = new QtCharts::QChart();
  chart->setTitle(QString::fromStdString(c.title));
  // Many series: one legend entry per row at the right, where no name is elided.
  chart->legend()->setAlignment(c.series.size() > 6 ? Qt::AlignRight : Qt::AlignBottom);
  QtCharts::QAbstractAxis* ax = nullptr;
  if (c.x_categories.empty()) {
    ax = makeAxis(c.log_x, c.x_label);
  } else {
    auto* cat = new QtCharts::QCategoryAxis();
    cat->setLabelsPosition(QtCharts::QCategoryAxis::AxisLabelsPositionOnValue);
    for (std::size_t i = 0; i < c.x_categories.size(); ++i)
      cat->append(QString::fromStdString(c.x_categories[i]), static_cast<double>(i));
    cat->setLabelsAngle(-60);  // long names side by side would be elided
    cat->setTitleText(QString::fromStdString(c.x_label));
    ax = cat;
  }
  auto* ay = makeAxis(c.log_y, c.y_label);
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
      if ((c.log_x && s.x[i] <= 0) || (c.log_y && s.y[i] <= 0)) continue;
      line->append(s.x[i], s.y[i]);
      xmin = std::min(xmin, s.x[i]);
      xmax = std::max(xmax, s.x[i]);
      ymin = std::min(ymin, s.y[i]);
      ymax = std::max(ymax, s.y[i]);
    }
    QPen pen(palette[(s.colour >= 0 ? s.colour : k) % 8]);
    pen.setWidth(3);
    if (s.dashed || (s.colour < 0 && k >= 8)) pen.setStyle(Qt::DashLine);  // past the palette: the colours again, dashed
    ++k;
    line->setPen(pen);
    line->setPointsVisible(true);
    chart->addSeries(line);
    line->attachAxis(ax);
    line->attachAxis(ay);
  }
  if (xmin > xmax) {  // no points: an empty frame (1…10 on a log axis)
    xmin = c.log_x ? 1 : 0, xmax = c.log_x ? 10 : 1;
    ymin = c.log_y ? 1 : 0, ymax = c.log_y ? 10 : 1;
  }
  if (std::isfinite(c.y_min)) ymin = c.y_min;
  if (std::isfinite(c.y_max)) ymax = c.y_max;
  if (ymax <= ymin) ymax = ymin + 1;
  if (xmax <= xmin) xmax = xmin + 1;
  if (!c.x_categories.empty()) ax->setRange(-0.5, static_cast<double>(c.x_categories.size()) - 0.5);
  else setRange(ax, c.log_x, xmin, xmax);
  setRange(ay, c.log_y, ymin, ymax);

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
  if (text) {
    for (const QGraphicsItem* item : scene.items(Qt::AscendingOrder)) {
      if (!item->isVisible()) continue;
      QString t;
      if (const auto* rich = dynamic_cast<const QGraphicsTextItem*>(item)) t = rich->toPlainText();
      else if (const auto* plain = dynamic_cast<const QGraphicsSimpleTextItem*>(item)) t = plain->text();
      if (!t.isEmpty()) text->push_back(t.toStdString());
    }
  }
  return img;
}

}  // namespace

std::vector<std::string> curvePlotText(const CurvePlot& c) {
  std::vector<std::string> text;
  drawCurve(c, &text);
  return text;
}

void saveCurvePng(const CurvePlot& c, const std::string& path) {
  const QImage img = drawCurve(c, nullptr);
  const std::filesystem::path target(path);
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path());
  if (!img.save(QString::fromStdString(path), "PNG")) throw Error(path + ": cannot write the chart PNG");
}

}  // namespace keyturn::plots
