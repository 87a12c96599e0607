#include "cli/huge_pages.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "common/memory.h"

#ifdef QUADCOVER_GLIBC_MALLOC
#include <malloc.h>
#endif

namespace quadcover::cli {
namespace {

/// Whether the kernel backs memory that asks for it (madvise MADV_HUGEPAGE) with huge pages, and only that.
[[maybe_unused]] bool huge_pages_on_request() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  std::getline(in, modes);
  return modes.find("[madvise]") != std::string::npos;
}

}  // namespace

void restart_with_huge_pages(char** argv) {
#ifdef QUADCOVER_GLIBC_MALLOC
  if (std::getenv("GLIBC_TUNABLES") || std::getenv(kNoHugePagesVariable) || !huge_pages_on_request()) return;
  // The program's own path, not /proc/self/exe: the process keeps its name (ps, top, pkill quadcover).
  std::error_code error;
  const std::string self = std::filesystem::read_symlink("/proc/self/exe", error).string();
  if (error || self.empty() || setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 0) != 0) return;
  const bool set_blas_threads = !std::getenv(kBlasThreadsVariable) && setenv(kBlasThreadsVariable, "1", 0) == 0;
  execv(self.c_str(), argv);
  unsetenv("GLIBC_TUNABLES");  // execv returned: it failed, run on as we are
  if (set_blas_threads) unsetenv(kBlasThreadsVariable);
#else
  (void)argv;
#endif
}

void use_one_heap_arena() {
#ifdef QUADCOVER_GLIBC_MALLOC
  mallopt(M_ARENA_MAX, 1);
#endif
}

}  // namespace quadcover::cli
