#include "enroll_dialog.h"

#include <QDialogButtonBox>
#include <QFormLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>

namespace keyturn::studio {

EnrollDialog::EnrollDialog(const QString& cls, const QString& instance, const QString& model, QWidget* parent)
    : QDialog(parent) {
  setWindowTitle(tr("Enroll the reconstructed object"));
  setObjectName("enrollDialog");
  auto* form = new QFormLayout(this);
  auto* about = new QLabel(tr("Its training views are rendered from the mesh through the simulated cameras and "
                              "added to %1; the new model is written beside it and recognition switches to it.")
                               .arg(model.toHtmlEscaped()));
  about->setWordWrap(true);
  form->addRow(about);
  cls_ = new QLineEdit(cls);
  cls_->setObjectName("enrollClass");
  instance_ = new QLineEdit(instance);
  instance_->setObjectName("enrollInstance");
  form->addRow(tr("Class"), cls_);
  form->addRow(tr("Instance"), instance_);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
  buttons->button(QDialogButtonBox::Ok)->setText(tr("Enroll"));
  form->addRow(buttons);
  connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  const auto update = [this, buttons] {
    buttons->button(QDialogButtonBox::Ok)->setEnabled(!this->cls().isEmpty() && !this->instance().isEmpty());
  };
  connect(cls_, &QLineEdit::textChanged, this, update);
  connect(instance_, &QLineEdit::textChanged, this, update);
  update();
}

QString EnrollDialog::cls() const { return cls_->text().trimmed(); }
QString EnrollDialog::instance() const { return instance_->text().trimmed(); }

}  // namespace keyturn::studio
