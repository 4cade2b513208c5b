#pragma once
// The C library's heap tuned for a program that describes view after view (docs/benchmarks.md,
// "Freed memory kept for the next view").
namespace keyturn::app {

// glibc gives freed memory at the top of its heap back to the kernel as soon as 128 KiB are free,
// so every view's buffers come back as fresh pages, each faulted in on first touch. Keeping 64 MiB
// makes the built-in SR4000 view 41 → 31 ms and a 640 × 480 frame 72 → 49 ms on this machine (the
// graph, the neighbourhood table and the filter's frame-sized buffers). A MALLOC_TOP_PAD_ the user
// set is left as it is; other C libraries are left alone.
void keepFreedHeapForReuse();

}  // namespace keyturn::app
