#include "keyturn/bench/startup_timing.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>

#include "keyturn/core/error.h"
#include "keyturn/core/string_format.h"
#include "spread.h"

namespace keyturn::bench {
namespace {

std::string joined(const std::vector<std::string>& argv) {
  std::string s;
  for (const auto& a : argv) s += (s.empty() ? "" : " ") + a;
  return s;
}

// One run: wall seconds from fork to the child's exit, its peak RSS (MiB) and exit code.
void runOnce(const std::vector<std::string>& argv, double& wall_s, double& peak_mib, int& code) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) throw Error(argv[0] + ": cannot start (fork failed)");
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) dup2(null, STDOUT_FILENO), dup2(null, STDERR_FILENO);
    execv(args[0], args.data());
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  if (wait4(pid, &status, 0, &usage) != pid) throw Error(argv[0] + ": lost the child process");
  wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  peak_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;  // kilobytes on Linux
  code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  if (code == 127) throw Error(argv[0] + ": cannot be run");
}

}  // namespace

ProcessTiming timeProcess(const std::string& label, const std::vector<std::string>& argv, int runs, int warmup) {
  if (argv.empty()) throw Error("timeProcess: no command");
  ProcessTiming t{label, argv, {}, {}, {}};
  for (int i = 0; i < warmup + runs; ++i) {
    double wall = 0, peak = 0;
    int code = 0;
    runOnce(argv, wall, peak, code);
    if (i < warmup) continue;
    t.wall_s.push_back(wall);
    t.peak_mib.push_back(peak);
    t.exit_codes.push_back(code);
  }
  return t;
}

nlohmann::json timingJson(const ProcessTiming& t) {
  const Spread w = spread(t.wall_s), m = spread(t.peak_mib);
  return {{"label", t.label},
          {"command", joined(t.argv)},
          {"runs", t.wall_s.size()},
          {"wall_s", {{"min", w.min}, {"median", w.median}, {"max", w.max}}},
          {"peak_mib", {{"min", m.min}, {"median", m.median}, {"max", m.max}}},
          {"exit_codes", t.exit_codes}};
}

std::string startupTable(const std::vector<ProcessTiming>& timings) {
  std::string out = "start-up (whole process, fork to exit)      wall s median (min-max)   peak MiB\n";
  for (const auto& t : timings) {
    const Spread w = spread(t.wall_s), m = spread(t.peak_mib);
    appendFormat(out, "%-44s %6.3f (%.3f-%.3f)     %8.1f\n", t.label.c_str(), w.median, w.min, w.max, m.median);
  }
  return out;
}

}  // namespace keyturn::bench
