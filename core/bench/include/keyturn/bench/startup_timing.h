#pragma once
// Start-up as a user meets it: a command run as a whole process, again and again, timed from
// fork to exit (wall) with its peak resident memory (the kernel's accounting of the finished
// child). `keyturn bench --startup` times `keyturn --help` and a one-view describe this way.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace keyturn::bench {

struct ProcessTiming {
  std::string label;
  std::vector<std::string> argv;
  std::vector<double> wall_s;
  std::vector<double> peak_mib;
  std::vector<int> exit_codes;
};

// Runs argv (argv[0] a path) `runs` times after `warmup` uncounted runs, its output to /dev/null.
// Throws keyturn::Error when the program cannot be started.
ProcessTiming timeProcess(const std::string& label, const std::vector<std::string>& argv, int runs, int warmup = 1);

// {"label", "command", "runs", "wall_s": {min, median, max}, "peak_mib": {…}, "exit_codes"}.
nlohmann::json timingJson(const ProcessTiming& t);

// One row per timing: label, median wall (min–max), median peak memory.
std::string startupTable(const std::vector<ProcessTiming>& timings);

}  // namespace keyturn::bench
