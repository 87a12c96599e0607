// The CLI's heap (cli/huge_pages.h): after use_one_heap_arena, a new thread allocates from the main heap instead of
// an arena of its own. Each check runs in a child process, since the setting is process-wide.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "cli/huge_pages.h"
#include "common/memory.h"

#ifdef QUADCOVER_GLIBC_MALLOC
#include <malloc.h>
#endif

namespace quadcover::cli {
namespace {

#ifdef QUADCOVER_GLIBC_MALLOC
/// The heaps (arenas) glibc's malloc_info lists after a new thread allocated, counted in a child process that first
/// calls use_one_heap_arena when `one_arena`; -1 if the child failed.
int heaps_after_a_thread_allocated(bool one_arena) {
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) return -1;
  const pid_t child = fork();
  if (child == 0) {
    if (one_arena) use_one_heap_arena();
    void* block = nullptr;
    std::thread([&block] { block = std::malloc(1000); }).join();
    char* text = nullptr;
    std::size_t size = 0;
    FILE* info = open_memstream(&text, &size);
    malloc_info(0, info);
    std::fclose(info);
    const std::string listed(text, size);
    int heaps = 0;
    for (std::size_t at = listed.find("<heap nr="); at != std::string::npos; at = listed.find("<heap nr=", at + 1))
      ++heaps;
    const bool written = write(pipe_ends[1], &heaps, sizeof heaps) == sizeof heaps;
    std::free(block);
    _exit(written ? 0 : 1);
  }
  close(pipe_ends[1]);
  int heaps = -1;
  if (read(pipe_ends[0], &heaps, sizeof heaps) != sizeof heaps) heaps = -1;
  close(pipe_ends[0]);
  int status = 0;
  waitpid(child, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? heaps : -1;
}

TEST(HeapArena, ANewThreadAllocatesFromTheMainHeapWithOneArena) {
  EXPECT_EQ(heaps_after_a_thread_allocated(false), 2);  // glibc's default: an arena for the thread
  EXPECT_EQ(heaps_after_a_thread_allocated(true), 1);
}
#endif  // a sanitizer's allocator has no arenas to count

}  // namespace
}  // namespace quadcover::cli
