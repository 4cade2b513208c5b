#include "status_label.h"

#include <QResizeEvent>
#include <algorithm>

namespace keyturn::studio {

QSize StatusLabel::minimumSizeHint() const { return {QLabel::minimumSizeHint().width(), textHeight()}; }

QSize StatusLabel::sizeHint() const { return {QLabel::sizeHint().width(), textHeight()}; }

void StatusLabel::resizeEvent(QResizeEvent* e) {
  QLabel::resizeEvent(e);
  if (e->size().width() != e->oldSize().width()) updateGeometry();
}

int StatusLabel::textHeight() const {
  return std::max(min_lines_ * fontMetrics().lineSpacing() + 4, heightForWidth(width()));
}

QString problemText(const QString& message) {
  QString html = message.toHtmlEscaped();
  html.replace('/', QStringLiteral("/\u200b"));
  return QString("<span style='color:#c0392b'>%1</span>").arg(html);
}

}  // namespace keyturn::studio
