#pragma once
// A device's status: wrapped, a long path (OpenNI2's drivers folders) breaking after its '/'s rather
// than running past the panel's edge, and as tall as its text at its width, so the panel grows by the
// lines a message takes instead of cutting them off (the scroll area around the panel asks it for one
// size, not for a height at its width: asked, QFormLayout answered for another width and cut the text
// off). A problem's whole message is the tooltip too.
#include <QLabel>

namespace keyturn::studio {

class StatusLabel final : public QLabel {
 public:
  StatusLabel(const QString& text, int min_lines) : QLabel(text), min_lines_(min_lines) { setWordWrap(true); }
  QSize minimumSizeHint() const override;
  QSize sizeHint() const override;
  // The layouts take the hints above, made at the label's width, not a height for a width they guess.
  bool hasHeightForWidth() const override { return false; }

 protected:
  void resizeEvent(QResizeEvent* e) override;

 private:
  int textHeight() const;
  int min_lines_;
};

// A problem as a status shows it, in red: escaped, a line break allowed after every '/'.
QString problemText(const QString& message);

}  // namespace keyturn::studio
