#include "job_status.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>

namespace keyturn::studio {

JobStatus::JobStatus(QWidget* parent) : QWidget(parent) {
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  label_ = new QLabel;
  label_->setObjectName("jobStatus");
  bar_ = new QProgressBar;
  bar_->setObjectName("jobProgress");
  bar_->setMaximumWidth(160);
  bar_->setMaximumHeight(16);
  bar_->hide();
  layout->addWidget(label_);
  layout->addWidget(bar_);
}

QString JobStatus::text() const { return plain_; }

void JobStatus::progress(const QString& stage, int done, int total) {
  failed_ = false;
  plain_ = total > 0 ? QString("%1: %2 / %3").arg(stage).arg(done).arg(total) : stage + "…";
  label_->setText(plain_.toHtmlEscaped());
  bar_->setRange(0, total);  // 0 – 0: a busy bar
  bar_->setValue(done);
  bar_->show();
}

void JobStatus::succeeded(const QString& text) {
  failed_ = false;
  plain_ = text;
  label_->setText(text.toHtmlEscaped());
  bar_->hide();
}

void JobStatus::fail(const QString& error) {
  failed_ = true;
  plain_ = error;
  label_->setText(QString("<span style='color:#c0392b'>%1</span>").arg(error.toHtmlEscaped()));
  bar_->hide();
}

}  // namespace keyturn::studio
