#include "job_status.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>

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
  cancel_ = new QPushButton(tr("Cancel"));
  cancel_->setObjectName("jobCancel");
  cancel_->setToolTip(tr("Stop the running job at its next step; what it would have written is not written"));
  cancel_->setMaximumHeight(20);
  cancel_->hide();
  connect(cancel_, &QPushButton::clicked, this, [this] {
    cancel_->setEnabled(false);  // until the job has stopped
    emit cancelRequested();
  });
  layout->addWidget(label_);
  layout->addWidget(bar_);
  layout->addWidget(cancel_);
}

void JobStatus::ended() {
  bar_->hide();
  cancel_->hide();
  cancel_->setEnabled(true);
}

QString JobStatus::text() const { return plain_; }

void JobStatus::progress(const QString& stage, int done, int total) {
  failed_ = false;
  plain_ = total > 0 ? QString("%1: %2 / %3").arg(stage).arg(done).arg(total) : stage + "…";
  label_->setText(plain_.toHtmlEscaped());
  bar_->setRange(0, total);  // 0 – 0: a busy bar
  bar_->setValue(done);
  bar_->show();
  cancel_->show();
}

void JobStatus::succeeded(const QString& text) {
  failed_ = false;
  plain_ = text;
  label_->setText(text.toHtmlEscaped());
  ended();
}

void JobStatus::fail(const QString& error) {
  failed_ = true;
  plain_ = error;
  label_->setText(QString("<span style='color:#c0392b'>%1</span>").arg(error.toHtmlEscaped()));
  ended();
}

}  // namespace keyturn::studio
