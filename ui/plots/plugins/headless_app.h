#pragma once
// Qt drawing needs a QApplication; a command-line tool may have none, and a
// headless machine no display (then the offscreen platform is chosen).
namespace keyturn::plots {

void ensureApplication();

}  // namespace keyturn::plots
