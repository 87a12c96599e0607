#pragma once
// The CLI's heap: transparent huge pages and one arena (and OpenBLAS started without its thread pool). glibc gives
// large blocks fresh pages from the kernel (mmap): on 10⁵ faces the solves then spend a fifth of their time in page
// faults. glibc's tunable glibc.malloc.hugetlb=1 makes malloc ask for transparent huge pages, with 5× fewer faults and
// the same peak (BENCHMARKS.md, "Transparent huge pages"). glibc reads tunables only when a process starts, so the CLI
// starts itself once more with the tunable set. Its threads share one heap (use_one_heap_arena), so that what one stage
// frees is reused by the next.

namespace quadcover::cli {

/// The environment variable that stops the restart (any value): QUADCOVER_NO_HUGE_PAGES.
inline constexpr const char* kNoHugePagesVariable = "QUADCOVER_NO_HUGE_PAGES";

/// The environment variable OpenBLAS reads when it starts: OPENBLAS_NUM_THREADS.
inline constexpr const char* kBlasThreadsVariable = "OPENBLAS_NUM_THREADS";

/// Executes this program again with GLIBC_TUNABLES=glibc.malloc.hugetlb=1 and the same arguments when all hold:
/// the C library is glibc, the build has no sanitizer, the kernel gives transparent huge pages on request
/// (/sys/kernel/mm/transparent_hugepage/enabled is "[madvise]"), GLIBC_TUNABLES and QUADCOVER_NO_HUGE_PAGES are
/// not set. The restarted program also gets OPENBLAS_NUM_THREADS=1 unless the variable is set: quadcover keeps BLAS on
/// one thread anyway (calculus/sparse_cholesky.cpp), and without it a threaded OpenBLAS starts a pool whose idle
/// threads call sched_yield for about 0.1 s, on the core the job's second thread needs (BENCHMARKS.md, "OpenBLAS
/// without its thread pool"). Returns when it does not restart, or when the restart fails (the environment is then
/// as it was).
/// \pre called first in main, before any thread, file or signal handler exists.
void restart_with_huge_pages(char** argv);

/// Makes every thread allocate from glibc's main heap (mallopt M_ARENA_MAX = 1). With an arena per thread, heap a
/// stage freed in one thread's arena stays resident while the next stage grows another's; one arena reuses it and
/// lowers the peak without giving memory back between stages (BENCHMARKS.md, "One heap arena"). Nothing without
/// glibc's malloc (a sanitizer's). \pre called in main before any thread exists.
void use_one_heap_arena();

}  // namespace quadcover::cli
