#include "keyturn/studio/studio_session.h"

#include <QApplication>
#include <QScreen>
#include <QTimer>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>

namespace keyturn::studio {
namespace {

std::atomic<bool> g_quit{false};
void onQuitSignal(int) { g_quit = true; }

}  // namespace

void catchQuitSignals() {
  struct sigaction sa {};
  sa.sa_handler = onQuitSignal;
  sigemptyset(&sa.sa_mask);
  struct sigaction old {};
  if (::sigaction(SIGINT, nullptr, &old) == 0 && old.sa_handler != SIG_IGN) ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);
}

void closeOnQuitSignal(QWidget& window) {
  auto* poll = new QTimer(&window);
  QObject::connect(poll, &QTimer::timeout, &window, [&window] {
    if (g_quit.exchange(false)) window.close();
  });
  poll->start(50);
}

std::string unknownSimObject(const std::vector<SimObject>& objects, const std::string& instance,
                             const std::string& objects_csv) {
  std::string known;
  for (const auto& o : objects) {
    if (o.instance == instance) return "";
    known += (known.empty() ? "" : ", ") + o.instance;
  }
  return "--object " + instance + ": not in " + objects_csv + " (" + known + ")";
}

void measureThenQuit(StudioWindow& window, double seconds, int threads, const std::string& screenshot,
                     double warmup_s) {
  auto start = std::make_shared<StudioRates>();
  QTimer::singleShot(static_cast<int>(warmup_s * 1000), &window, [&window, start] { *start = window.rates(); });
  QTimer::singleShot(static_cast<int>((warmup_s + seconds) * 1000), &window, [&window, start, seconds, threads, screenshot] {
    const auto end = window.rates();
    const double frames = static_cast<double>(end.frames - start->frames) / seconds;
    const double results = static_cast<double>(end.results - start->results) / seconds;
    std::printf("{\"seconds\": %.1f, \"camera_fps\": %.2f, \"recognition_fps\": %.2f, \"latency_ms\": %.1f, "
                "\"describe_ms\": %.1f, \"dropped\": %ld, \"threads\": %d, \"class\": \"%s\", \"agreement\": %.2f}\n",
                seconds, frames, results, end.latency_ms, end.describe_ms, end.dropped - start->dropped, threads,
                window.recognisedClass().toStdString().c_str(), window.recognisedAgreement());
    std::fflush(stdout);
    // From the display, not grab(): the 3D view is a native OpenGL window grab() cannot see.
    QScreen* screen = window.screen();
    const QRect g = window.frameGeometry();
    if (!screenshot.empty() &&
        !(screen ? screen->grabWindow(0, g.x(), g.y(), g.width(), g.height()) : window.grab())
             .save(QString::fromStdString(screenshot)))
      std::cerr << "keyturn-studio: cannot write " << screenshot << "\n";
    window.close();
    QApplication::quit();
  });
}

}  // namespace keyturn::studio
