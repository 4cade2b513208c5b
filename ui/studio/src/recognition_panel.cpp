#include "recognition_panel.h"

#include <QComboBox>
#include <QDateTime>
#include <QFontMetrics>
#include <QFileDialog>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QVBoxLayout>
#include <QtCharts/QChart>
#include <QtCharts/QChartView>
#include <QtCharts/QLineSeries>
#include <QtCharts/QValueAxis>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "keyturn/core/features.h"

using namespace QtCharts;

namespace keyturn::studio {

namespace {
constexpr int kTop = 5;
// Stability labels beside the class indices: an open-set model's "unknown" and a view too empty to
// describe (issue 34), so the verdict can settle on either as on a class.
constexpr int kUnknown = -2, kNoObject = -3;
const char* kUnknownColour = "#8e44ad";
const char* kNoObjectColour = "#7f8c8d";
}

RecognitionPanel::RecognitionPanel(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  auto* model_box = new QGroupBox(tr("Model"));
  auto* ml = new QVBoxLayout(model_box);
  auto* row = new QHBoxLayout;
  model_path_ = new QLineEdit;
  model_path_->setObjectName("modelPath");
  model_path_->setPlaceholderText(tr("model folder (keyturn train --out …)"));
  auto* browse = new QPushButton(tr("Load…"));
  browse->setShortcut(QKeySequence(Qt::CTRL | Qt::Key_O));
  browse->setToolTip(tr("Load a model folder (Ctrl+O)"));
  row->addWidget(model_path_, 1);
  row->addWidget(browse);
  ml->addLayout(row);
  model_info_ = new QLabel(tr("no model: views are described, not classified"));
  model_info_->setWordWrap(true);
  ml->addWidget(model_info_);
  layout->addWidget(model_box);

  auto* top = new QGroupBox(tr("Current view"));
  auto* grid = new QGridLayout(top);
  verdict_ = new QLabel("–");
  verdict_->setObjectName("verdict");
  QFont big = verdict_->font();
  big.setPointSizeF(big.pointSizeF() * 1.6);
  big.setBold(true);
  verdict_->setFont(big);
  // Its own line's height however the box is squeezed, and a long name never widens the dock.
  verdict_->setMinimumHeight(QFontMetrics(big).height() + 2);
  verdict_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
  // The name is the last 20 frames' verdict, the small figures this frame's own test: the two can
  // differ ("ycb_035_power_drill 0.35 < 0.43"), so the tooltip says which is which.
  verdict_->setToolTip(tr("The answer most of the last 20 frames agree on; beside it, this frame's open-set score "
                          "against the model's threshold (under it: this frame alone is unknown)"));
  grid->addWidget(verdict_, 0, 0, 1, 2);
  // The belief fused over the views of the table's turn, under the single view's (issue 34): one
  // line, so the window still fits a 1000 px screen.
  fused_verdict_ = new QLabel("–");
  fused_verdict_->setObjectName("fusedVerdict");
  fused_verdict_->setToolTip(tr("The belief fused over the views of the table's turn (one per 5°), beside this view's"));
  fused_verdict_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);  // a long name never widens the dock
  grid->addWidget(fused_verdict_, 1, 0, 1, 2);
  for (int i = 0; i < kTop; ++i) {
    auto* name = new QLabel;
    auto* bar = new QProgressBar;
    bar->setRange(0, 1000);
    bar->setTextVisible(true);
    bar->setFormat("");
    bar->setMaximumHeight(16);
    grid->addWidget(name, i + 2, 0);
    grid->addWidget(bar, i + 2, 1);
    names_.push_back(name);
    bars_.push_back(bar);
  }
  grid->setColumnStretch(1, 1);
  stability_label_ = new QLabel("–");
  stability_label_->setObjectName("stability");
  keypoints_ = new QLabel("–");
  keypoints_->setObjectName("keypointCount");
  grid->addWidget(new QLabel(tr("Stability")), kTop + 2, 0);
  grid->addWidget(stability_label_, kTop + 2, 1);
  grid->addWidget(new QLabel(tr("Keypoints")), kTop + 3, 0);
  grid->addWidget(keypoints_, kTop + 3, 1);
  layout->addWidget(top);


  auto* pdf_box = new QGroupBox(tr("PDFs over their bins: this view and the class mean"));
  auto* pl = new QVBoxLayout(pdf_box);
  block_ = new QComboBox;
  pl->addWidget(block_);
  chart_ = new QChart;
  chart_->setMargins(QMargins(2, 2, 2, 2));
  // The series are named in a line above the chart, not in its legend, and the x axis has no
  // title (the bins are in the box's title): in a 140 px chart Qt Charts gave the legend and
  // title the height first and elided every x label to "…".
  chart_->legend()->hide();
  pdf_legend_ = new QLabel;
  pdf_legend_->setObjectName("pdfLegend");
  pdf_legend_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);  // a long class name never widens the dock
  pl->addWidget(pdf_legend_);
  view_series_ = new QLineSeries;
  view_series_->setPen(QPen(QColor(41, 128, 185), 2));
  mean_series_ = new QLineSeries;
  mean_series_->setPen(QPen(QColor(230, 126, 34), 2, Qt::DashLine));
  showPdfLegend(QString());
  chart_->addSeries(mean_series_);
  chart_->addSeries(view_series_);
  x_axis_ = new QValueAxis;
  y_axis_ = new QValueAxis;
  QFont small = chart_->font();
  small.setPointSizeF(std::max(6.0, small.pointSizeF() * 0.75));
  for (auto* axis : {x_axis_, y_axis_}) axis->setLabelsFont(small);
  x_axis_->setLabelFormat("%d");
  x_axis_->setTickType(QValueAxis::TicksDynamic);  // whole bins: 0, B/4, B/2, …
  x_axis_->setTickAnchor(0);
  x_axis_->setTickInterval(8);  // never 0: a dynamic axis with no interval makes ticks without end
  y_axis_->setLabelFormat("%.2f");
  y_axis_->setTickCount(3);
  chart_->addAxis(x_axis_, Qt::AlignBottom);
  chart_->addAxis(y_axis_, Qt::AlignLeft);
  for (auto* s : {view_series_, mean_series_}) {
    s->attachAxis(x_axis_);
    s->attachAxis(y_axis_);
  }
  auto* view = new QChartView(chart_);
  view->setRenderHint(QPainter::Antialiasing);
  view->setMinimumHeight(120);  // grows with the dock; at 220 the window did not fit a 1000 px screen
  pl->addWidget(view, 1);
  layout->addWidget(pdf_box, 1);

  connect(browse, &QPushButton::clicked, this, [this] {
    const QString d = QFileDialog::getExistingDirectory(this, tr("Model folder"), model_path_->text());
    if (!d.isEmpty()) emit loadModel(d);
  });
  connect(model_path_, &QLineEdit::returnPressed, this, [this] { emit loadModel(model_path_->text()); });
}

void RecognitionPanel::setModel(const QString& path, const learning::Recognizer* recognizer, const QString& error) {
  model_path_->setText(path);
  stability_.clear();
  classes_.clear();
  block_->clear();
  if (!error.isEmpty()) {
    model_info_->setText(QString("<span style='color:#c0392b'>%1</span>").arg(error.toHtmlEscaped()));
    return;
  }
  if (!recognizer) return;
  // Each PDF by its index among the view's blocks; the keypoints themselves (a set network's "kpset")
  // are no PDF, and the 3D view already shows them.
  const auto names = recognizer->blockNames();
  for (std::size_t k = 0; k < names.size(); ++k)
    if (names[k] != "kpset") block_->addItem(QString::fromStdString(names[k]), static_cast<int>(k));
  if (!recognizer->hasModel()) {
    model_info_->setText(tr("no model: views are described, not classified"));
    return;
  }
  const auto& info = recognizer->info();
  classes_ = info.classes;
  QStringList blocks;
  for (const auto& b : info.blocks) blocks << QString::fromStdString(b);
  const QString open_set = info.open_set.enabled()
                               ? tr("open-set: %1 at %2 %").arg(QString::fromStdString(info.open_set.method))
                                     .arg(100 * info.open_set.false_accept, 0, 'g', 3)
                               : tr("closed-set");
  model_info_->setText(QString("%1 · %2 classes · %3 · %4 bins · %5 · %6")
                           .arg(QString::fromStdString(info.params.kind))
                           .arg(info.classes.size())
                           .arg(blocks.join("+"))
                           .arg(QString::fromStdString(info.spec.at("bins")))
                           .arg(open_set)
                           .arg(info.pose_references.empty() ? tr("fuses a turn's views independently (no pose references)")
                                                             : tr("fuses by pose")));
}

void RecognitionPanel::showFusion(const learning::LiveFusion& f) {
  const std::vector<double> belief = f.belief();
  fused_views_ = static_cast<int>(f.views());
  fused_belief_ = 0;
  if (classes_.empty() || f.views() == 0) {
    fused_class_.clear();
    fused_verdict_->setText(QString("%1 <span style='color:%2'>%3</span>")
                                .arg(tr("Turn:"), kNoObjectColour,
                                     classes_.empty() ? tr("no model") : tr("no view yet: turn the table")));
    return;
  }
  const learning::Answer answer = f.answer();
  const bool named = belief.size() == classes_.size();
  const int best = named ? f.best() : -1;
  QString colour;
  if (answer == learning::Answer::Unknown) {
    fused_class_ = QStringLiteral("unknown");
    colour = kUnknownColour;
  } else if (answer == learning::Answer::NoObject || best < 0) {
    fused_class_ = QStringLiteral("no object");
    colour = kNoObjectColour;
  } else {
    fused_class_ = QString::fromStdString(classes_[static_cast<std::size_t>(best)]);
    fused_belief_ = belief[static_cast<std::size_t>(best)];
    colour = fused_belief_ >= 0.99 ? "#27ae60" : fused_belief_ >= 0.8 ? "#d68910" : "#c0392b";
  }
  QString detail = answer == learning::Answer::Class && best >= 0 ? QString(" %1 %").arg(100.0 * fused_belief_, 0, 'f', 1) : QString();
  detail += QString(" · %1 %2, %3°")
                .arg(f.views())
                .arg(f.views() == 1 ? tr("view") : tr("views"))
                .arg(f.turnedDeg(), 0, 'f', 0);
  if (f.unknownViews() > 0) detail += tr(" · %1 unknown").arg(f.unknownViews());
  fused_verdict_->setText(QString("%1 <b style='color:%2'>%3</b><span style='color:%4'>%5</span>")
                              .arg(tr("Turn:"), colour, fused_class_.toHtmlEscaped(), kNoObjectColour, detail.toHtmlEscaped()));
  // One line in a narrow dock cuts a long class name's details: the tooltip has them whole.
  fused_verdict_->setToolTip(tr("The belief fused over the views of the table's turn (one per 5°), beside this view's:\n%1%2")
                                 .arg(fused_class_, detail));
}

QString RecognitionPanel::modelPath() const { return model_path_->text(); }

QString RecognitionPanel::stableClass() const {
  const int m = stability_.mode();
  if (m == kUnknown) return QStringLiteral("unknown");
  if (m == kNoObject) return QStringLiteral("no object");
  return m >= 0 && m < static_cast<int>(classes_.size()) ? QString::fromStdString(classes_[static_cast<std::size_t>(m)]) : QString();
}

void RecognitionPanel::showVerdict(const QString& detail) {
  const double a = stability_.agreement();
  const int m = stability_.mode();
  const QString agree = a >= 0.8 ? "#27ae60" : a >= 0.5 ? "#d68910" : "#c0392b";
  const QString colour = m == kUnknown ? kUnknownColour : m == kNoObject ? kNoObjectColour : agree;
  stability_label_->setText(QString("<span style='color:%1'>●</span> %2 / %3 frames agree")
                                .arg(agree)
                                .arg(stability_.agreeing())
                                .arg(stability_.frames()));
  verdict_->setText(QString("<span style='color:%1'>%2</span><span style='color:%3;font-size:small'>%4</span>")
                        .arg(colour, stableClass().toHtmlEscaped(), kNoObjectColour, detail.toHtmlEscaped()));
}

void RecognitionPanel::record(const ViewResultPtr& result) {
  if (!result) return;
  latest_ = result;
  fresh_ = true;
  const auto* rec = result->recognition.get();
  if (rec && !rec->probabilities.empty() && rec->probabilities.size() == classes_.size())
    stability_.add(rec->answer == learning::Answer::Unknown ? kUnknown : rec->best);
  else if (!rec && result->no_object && !classes_.empty())
    stability_.add(kNoObject);
}

void RecognitionPanel::refresh() {
  if (!fresh_ || !latest_) return;
  fresh_ = false;
  const ViewResultPtr result = latest_;
  if (!result->recognition) {
    const QString why = QString::fromStdString(result->error).toHtmlEscaped();
    keypoints_->setText(result->no_object ? QString("<span style='color:%1'>no object: %2</span>").arg(kNoObjectColour, why)
                                          : QString("<span style='color:#c0392b'>%1</span>").arg(why));
    if (result->no_object && !classes_.empty()) showVerdict({});
    return;
  }
  const auto& rec = *result->recognition;
  const int k = rec.descriptor.keypointCount();
  keypoints_->setText(rec.descriptor.low_keypoints
                          ? QString("<span style='color:#d35400'>K = %1: few keypoints, a thin histogram</span>").arg(k)
                          : QString("K = %1 in %2 points").arg(k).arg(rec.filtered.size()));
  if (!rec.probabilities.empty() && rec.probabilities.size() == classes_.size()) {
    std::vector<int> order(rec.probabilities.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return rec.probabilities[a] > rec.probabilities[b]; });
    for (int i = 0; i < kTop; ++i) {
      const bool has = i < static_cast<int>(order.size());
      names_[i]->setText(has ? QString::fromStdString(classes_[order[i]]) : QString());
      bars_[i]->setValue(has ? static_cast<int>(1000 * rec.probabilities[order[i]]) : 0);
      bars_[i]->setFormat(has ? QString("%1 %").arg(100.0 * rec.probabilities[order[i]], 0, 'f', 1) : QString());
    }
    // An open-set model's test of this view: its score against the threshold (the model line names the method).
    const learning::OpenSet& open = result->recognizer->info().open_set;
    showVerdict(open.enabled() && std::isfinite(rec.score)
                    ? QString("  %1 %2 %3")
                          .arg(rec.score, 0, 'f', 2)
                          .arg(rec.answer == learning::Answer::Class ? ">=" : "<")
                          .arg(open.threshold, 0, 'f', 2)
                    : QString());
  }
  // The chart at a few frames per second is enough for the eye.
  const qint64 now = QDateTime::currentMSecsSinceEpoch();
  if (now - last_plot_ms_ >= 400) {
    last_plot_ms_ = now;
    plot(*result);
  }
}

void RecognitionPanel::plot(const ViewResult& r) {
  const auto& rec = *r.recognition;
  if (block_->currentIndex() < 0) return;
  const int b = block_->currentData().toInt();
  if (b < 0 || b >= static_cast<int>(rec.blocks.size())) return;
  const auto& pdf = rec.blocks[static_cast<std::size_t>(b)];
  QVector<QPointF> view, mean;
  double top = 0;
  for (std::size_t i = 0; i < pdf.size(); ++i) {
    view.append(QPointF(static_cast<double>(i), pdf[i]));
    top = std::max(top, pdf[i]);
  }
  const auto& info = r.recognizer->info();
  const int best = stability_.mode();
  if (r.recognizer->hasModel() && best >= 0 && best < static_cast<int>(info.class_means.size())) {
    const auto& m = info.class_means[static_cast<std::size_t>(best)];
    std::size_t offset = 0;  // the block's first input
    for (int k = 0; k < b; ++k) offset += rec.blocks[static_cast<std::size_t>(k)].size();
    for (std::size_t i = 0; i < pdf.size() && offset + i < m.size(); ++i) {
      mean.append(QPointF(static_cast<double>(i), m[offset + i]));
      top = std::max(top, static_cast<double>(m[offset + i]));
    }
    showPdfLegend(QString::fromStdString(info.classes[static_cast<std::size_t>(best)]));
  }
  view_series_->replace(view);
  mean_series_->replace(mean);
  x_axis_->setRange(0, std::max<double>(1, static_cast<double>(pdf.size()) - 1));
  x_axis_->setTickInterval(std::max(1.0, std::round(static_cast<double>(pdf.size()) / 4.0)));
  y_axis_->setRange(0, top > 0 ? top * 1.1 : 1);
}

void RecognitionPanel::showPdfLegend(const QString& cls) {
  pdf_legend_->setText(QString("<span style='color:#2980b9'>━ %1</span> &nbsp; <span style='color:#e67e22'>╍ %2</span>")
                           .arg(tr("this view"), (cls.isEmpty() ? tr("class mean") : tr("mean of %1").arg(cls)).toHtmlEscaped()));
}

}  // namespace keyturn::studio
