#pragma once
// Items 0 … n-1 handed out one at a time to worker threads (the caller's own
// thread among them), for per-view and per-fold work of uneven cost.
#include <cstddef>
#include <functional>

namespace keyturn {

// jobs ≤ 0: one thread per core; never more threads than items. body runs on several
// threads at once. If it throws, no further items are started, the running ones finish,
// and the first exception is rethrown on the caller's thread.
void parallelFor(std::size_t n, int jobs, const std::function<void(std::size_t i)>& body);

}  // namespace keyturn
