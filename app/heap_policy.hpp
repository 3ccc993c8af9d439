#pragma once
// glibc's heap thresholds, a policy of the whole process: set once at the program's start
// (main.cpp, and fetic-bench-scale's main), beside the glibc.malloc.hugetlb tunable.

namespace fetic::app {

// glibc's heap thresholds fixed at the values its own rule reaches after the first large
// free (mmap 32 MB, trim twice that). At the start-up defaults (128 KB) each subdomain's
// temporaries above 128 KB (CHOLMOD's workspace, K_j) are mapped and unmapped, and the
// heaps trimmed and grown, subdomain after subdomain: at 984,900 unknowns 239,000 page
// faults instead of 59,000 and the factorization 1.5x slower, once the set-up no longer
// freed a large grown array before it (which had raised them by accident). Does nothing
// outside glibc.
void keep_freed_heap_for_reuse();

}  // namespace fetic::app
