#pragma once
// Enroll…'s question: the class and the instance the reconstructed object is added to the model as.
#include <QDialog>

class QLineEdit;

namespace keyturn::studio {

class EnrollDialog : public QDialog {
  Q_OBJECT
 public:
  EnrollDialog(const QString& cls, const QString& instance, const QString& model, QWidget* parent = nullptr);
  QString cls() const;
  QString instance() const;

 private:
  QLineEdit *cls_, *instance_;
};

}  // namespace keyturn::studio
