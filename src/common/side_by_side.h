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

/// Runs `first` and `second` side by side when side_by_side(faces), else one after the other. Either way an
/// exception of `first` is the one thrown when both throw, as when they run in order. \pre none
template <class First, class Second>
void run_side_by_side(int faces, First&& first, Second&& second) {
  if (!side_by_side(faces)) {
    first();
    second();
    return;
  }
  std::exception_ptr first_error, second_error;
  tbb::parallel_invoke(
      [&] {
        try {
          first();
        } catch (...) {
          first_error = std::current_exception();
        }
      },
      [&] {
        try {
          second();
        } catch (...) {
          second_error = std::current_exception();
        }
      });
  if (first_error) std::rethrow_exception(first_error);
  if (second_error) std::rethrow_exception(second_error);
}

}  // namespace quadcover
