#include "keyturn/core/worker_process.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <mutex>

#include "keyturn/core/error.h"
#include "keyturn/core/plugin.h"
#include "worker_protocol.h"

extern char** environ;

namespace keyturn {
namespace {

struct Worker {
  pid_t pid = -1;
  int socket = -1;
};

std::atomic<int> started{0};

// Idle workers, kept for the next call; never destroyed (a worker ends when this process's end
// of its socket closes, at exit).
std::mutex idle_mutex;
std::vector<Worker>& idleWorkers() {
  static auto* idle = new std::vector<Worker>;
  return *idle;
}

Worker spawnWorker(const std::string& name) {
  const std::string program = pluginFile("keyturn-worker", name + ": the worker program").string();
  int ends[2];
  // Close-on-exec: a program another thread spawns meanwhile must not hold this socket open.
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0)
    throw Error(name + ": cannot create a socket for the worker");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, ends[1], STDIN_FILENO);  // dup2 clears close-on-exec
  posix_spawn_file_actions_adddup2(&actions, ends[1], STDOUT_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  char* argv[] = {const_cast<char*>(program.c_str()), nullptr};
  pid_t pid = -1;
  const int failed = ::posix_spawn(&pid, program.c_str(), &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(ends[1]);
  if (failed) {
    ::close(ends[0]);
    throw Error(name + ": cannot start " + program + " (" + std::strerror(failed) + ")");
  }
  ++started;
  return {pid, ends[0]};
}

// An idle worker when there is one (`reused` says so), else a new one.
Worker takeWorker(const std::string& name, bool& reused) {
  reused = false;
  {
    std::lock_guard<std::mutex> lock(idle_mutex);
    auto& idle = idleWorkers();
    if (!idle.empty()) {
      const Worker w = idle.back();
      idle.pop_back();
      reused = true;
      return w;
    }
  }
  return spawnWorker(name);
}

// The worker's exit status, once its socket is closed (it has ended, or ends now it reads EOF).
int reap(Worker& w) {
  ::close(w.socket);
  int status = 0;
  while (::waitpid(w.pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

bool sendRequest(const Worker& w, const WorkerJob& request) {
  const auto job_size = static_cast<std::uint32_t>(request.job.size());
  const auto n = static_cast<std::uint32_t>(request.input.size());
  return worker::writeAll(w.socket, &job_size, sizeof job_size) &&
         worker::writeAll(w.socket, request.job.data(), job_size) && worker::writeAll(w.socket, &n, sizeof n) &&
         worker::writeAll(w.socket, request.input.data(), n * sizeof(float));
}

}  // namespace

int workerProcessesStarted() { return started.load(); }

std::vector<float> inWorkerProcess(const WorkerJob& request, const std::string& name, const std::string& crashed,
                                   const std::string& where) {
  bool reused = false;
  Worker w = takeWorker(name, reused);
  if (!sendRequest(w, request)) {
    reap(w);
    if (!reused) throw Error(name + ": the worker process does not take requests");
    w = spawnWorker(name);  // an idle worker that ended meanwhile (killed): a new one
    if (!sendRequest(w, request)) {
      reap(w);
      throw Error(name + ": the worker process does not take requests");
    }
  }
  std::uint8_t status = worker::kFailed;
  std::uint32_t n = 0;
  bool replied = worker::readAll(w.socket, &status, sizeof status) &&
                 worker::readAll(w.socket, &n, sizeof n);
  std::vector<float> out;
  std::string message;
  if (replied && status == worker::kDone) {
    out.resize(n);
    replied = worker::readAll(w.socket, out.data(), n * sizeof(float));
  } else if (replied) {
    message.resize(n);
    replied = worker::readAll(w.socket, message.data(), n);
  }
  if (!replied) {
    const int exit = reap(w);
    if (WIFSIGNALED(exit)) throw Error(crashed + " (signal " + std::to_string(WTERMSIG(exit)) + ", " + where + ")");
    throw Error(name + ": the worker process ended without an answer");
  }
  {
    std::lock_guard<std::mutex> lock(idle_mutex);
    idleWorkers().push_back(w);
  }
  if (status != worker::kDone) throw Error(name + ": " + message);
  return out;
}

}  // namespace keyturn
