#include "heap_reuse.h"

#include <cstdlib>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace keyturn::app {

void keepFreedHeapForReuse() {
#if defined(__GLIBC__)
  if (std::getenv("MALLOC_TOP_PAD_") == nullptr) mallopt(M_TOP_PAD, 64 << 20);
#endif
}

}  // namespace keyturn::app
