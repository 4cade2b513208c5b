// Linked into every gtest binary: a test that dies of a signal prints its thread's stack before it
// dies, so that a crash seen once in a suite run (issue 51: a SIGSEGV after 1.64 s that 150 runs
// did not repeat) leaves more than "Exception: SegFault" behind. The frames are addresses in each
// module (`addr2line -f -C -e MODULE +OFFSET` names them); the signal is then raised again with its
// default action, so ctest still sees the crash and a core is dumped where cores are on.
// Not under AddressSanitizer, which reports such signals itself with symbolised stacks.
#include <execinfo.h>
#include <signal.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <initializer_list>

#include "support/under_asan.h"

namespace {

void say(const char* text) {
  for (std::size_t left = std::strlen(text); left > 0;) {
    const ssize_t n = write(STDERR_FILENO, text, left);
    if (n <= 0) return;
    text += n, left -= std::size_t(n);
  }
}

// Only async-signal-safe calls: write, snprintf into a stack buffer, and backtrace, whose one unsafe
// step (loading the unwinder) is done before any signal, at install.
void printStackAndDie(int sig, siginfo_t* info, void*) {
  char line[160];
  std::snprintf(line, sizeof line, "\n*** test process %d, thread %ld: signal %d (%s), fault address %p; stack:\n",
                int(getpid()), long(syscall(SYS_gettid)), sig, sigabbrev_np(sig) ? sigabbrev_np(sig) : "?",
                info ? info->si_addr : nullptr);
  say(line);
  void* frames[64];
  const int n = backtrace(frames, 64);
  backtrace_symbols_fd(frames, n, STDERR_FILENO);
  say("*** end of stack\n");
  raise(sig);  // SA_RESETHAND put the default action back: the process ends as it would have
}

bool install() {
#ifndef KEYTURN_UNDER_ASAN
  void* warm[1];
  backtrace(warm, 1);
  // A stack overflow leaves no stack to run the handler on: give the main thread a spare one.
  static char spare[1 << 16];
  stack_t ss{};
  ss.ss_sp = spare;
  ss.ss_size = sizeof spare;
  sigaltstack(&ss, nullptr);
  struct sigaction sa {};
  sa.sa_sigaction = printStackAndDie;
  sa.sa_flags = SA_SIGINFO | SA_RESETHAND | SA_ONSTACK;
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT}) sigaction(sig, &sa, nullptr);
#endif
  return true;
}

const bool installed = install();

}  // namespace
