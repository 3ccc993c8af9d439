#include "app/heap_policy.hpp"

#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace fetic::app {

void keep_freed_heap_for_reuse() {
#ifdef __GLIBC__
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 64 << 20);
#endif
}

}  // namespace fetic::app
