#pragma once
// Recognition: the model, the current view's top classes with probabilities,
// how steady the answer has been over the last frames, the belief fused over
// the views of the table's turn beside it, and the view's PDFs drawn over the
// mean PDFs of the class it was recognised as.
#include <QWidget>

#include "frame_types.h"
#include "keyturn/learning/live_fusion.h"
#include "stability.h"

class QComboBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;

namespace QtCharts {
class QChart;
class QChartView;
class QLineSeries;
class QValueAxis;
}  // namespace QtCharts

namespace keyturn::studio {

class RecognitionPanel : public QWidget {
  Q_OBJECT
 public:
  explicit RecognitionPanel(QWidget* parent = nullptr);
  void setModel(const QString& path, const learning::Recognizer* recognizer, const QString& error = {});
  QString modelPath() const;
  // The class the last N frames agree on ("" before any; "unknown" for an open-set model's views
  // unlike every class, "no object" for views too empty to describe), and that agreement.
  QString stableClass() const;
  double stableAgreement() const { return stability_.agreement(); }
  // The fused answer over the turn's views ("" before any; "unknown" as for a view) and their count.
  QString fusedClass() const { return fused_class_; }
  int fusedViews() const { return fused_views_; }
  double fusedBelief() const { return fused_belief_; }  // the fused answer's belief (0 unless a class)
  void showFusion(const learning::LiveFusion& fusion);

 public slots:
  // Every result counts towards stability; refresh() draws the newest.
  void record(const keyturn::studio::ViewResultPtr& result);
  void refresh();

 signals:
  void loadModel(const QString& path);

 private:
  void plot(const ViewResult& r);
  // The stability line and the verdict (with `detail` after it, small), coloured by agreement,
  // purple for unknown, grey for no object.
  void showVerdict(const QString& detail);
  void showPdfLegend(const QString& cls);  // the series named above the chart; cls empty: no class yet

  QLineEdit* model_path_;
  QLabel *model_info_, *keypoints_, *stability_label_, *verdict_;
  std::vector<QLabel*> names_;
  std::vector<QProgressBar*> bars_;
  QLabel* fused_verdict_;
  QLabel* pdf_legend_;
  QString fused_class_;
  double fused_belief_ = 0;
  int fused_views_ = 0;
  QComboBox* block_;
  QtCharts::QChart* chart_;
  QtCharts::QLineSeries *view_series_, *mean_series_;
  QtCharts::QValueAxis *x_axis_, *y_axis_;
  Stability stability_{20};
  std::vector<std::string> classes_;
  qint64 last_plot_ms_ = 0;
  ViewResultPtr latest_;
  bool fresh_ = false;
};

}  // namespace keyturn::studio
