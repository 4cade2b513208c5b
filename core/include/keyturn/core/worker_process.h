#pragma once
// Running code that may crash the process (a third-party routine with a known abort no input
// check predicts) in a separate worker process: keyturn-worker, a program beside the plugins
// (plugin.h's folders), started with posix_spawn and kept for the next call. Its result comes
// back through a socket, and a crash becomes a keyturn::Error instead of taking the caller down.
// The worker's stderr goes to /dev/null (the caller reports).
//
// Why a program and not fork(): a fork beside other running threads copies their locks as they
// are, and the child's first allocation deadlocked on one (clang 14's ASan allocator, a describe
// on two threads, issue 51). A spawned program starts with one thread and its own heap.
#include <string>
#include <vector>

namespace keyturn {

// What the worker is asked for: a job it knows (see core/worker/keyturn_worker.cpp) and its input.
struct WorkerJob {
  std::string job;
  std::vector<float> input;
};

// Runs `request` in a worker and returns its output. Throws keyturn::Error:
//   "NAME: ..." when the worker cannot be found or started, or the job failed in it (its message);
//   "CRASHED (signal N, WHERE)" when the worker died on a signal (a new one serves the next call).
std::vector<float> inWorkerProcess(const WorkerJob& request, const std::string& name, const std::string& crashed,
                                   const std::string& where);

// How many worker processes this process has started (one per thread that called at the same
// time, more after crashes): for the tests.
int workerProcessesStarted();

}  // namespace keyturn
