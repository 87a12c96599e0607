#pragma once
// Two independent solves of one mesh: side by side on small meshes, one after the other on large ones.
#include <exception>
#include <tbb/parallel_invoke.h>

namespace quadcover {

/// Below this many faces two independent solves of one mesh run side by side, one per core (about 1.4× faster);
/// from it on one after the other: side by side they raised a stage's peak memory by 40 % (BENCHMARKS.md, "Under
/// 3 KB per face"), on smaller meshes a few hundred MB at most.
constexpr int kSideBySideFaces = 100000;

/// Whether two solves of a mesh with `faces` faces run side by side. \pre none
constexpr bool side_by_side(int faces) { return faces < kSideBySideFaces; }

namespace detail {
/// How many run_side_by_side branches the calling thread is inside.
inline thread_local int side_by_side_depth = 0;

/// Runs `solve` as a branch of run_side_by_side, keeping its exception in `error`.
template <class Solve>
void run_branch(Solve& solve, std::exception_ptr& error) {
  ++side_by_side_depth;
  try {
    solve();
  } catch (...) {
    error = std::current_exception();
  }
  --side_by_side_depth;
}
}  // namespace detail

/// Runs `first` and `second` side by side when side_by_side(faces), else one after the other; also one after the
/// other inside a branch of an outer pair (both cores are busy with that pair already: side by side the inner pair
/// would only hold both its solves' memory at once). Either way an exception of `first` is the one thrown when both
/// throw, as when they run in order. \pre none
template <class First, class Second>
void run_side_by_side(int faces, First&& first, Second&& second) {
  if (!side_by_side(faces) || detail::side_by_side_depth > 0) {
    first();
    second();
    return;
  }
  std::exception_ptr first_error, second_error;
  tbb::parallel_invoke([&] { detail::run_branch(first, first_error); },
                       [&] { detail::run_branch(second, second_error); });
  if (first_error) std::rethrow_exception(first_error);
  if (second_error) std::rethrow_exception(second_error);
}

}  // namespace quadcover
