// Two solves side by side (common/side_by_side.h) and the sink they share (common/progress.h SerializedProgress).
#include "common/side_by_side.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>

#include "common/progress.h"

namespace quadcover {
namespace {

TEST(SideBySide, SmallMeshesRunBothLargeOnesInOrder) {
  EXPECT_TRUE(side_by_side(kSideBySideFaces - 1));
  EXPECT_FALSE(side_by_side(kSideBySideFaces));
  for (const int faces : {10, kSideBySideFaces}) {
    std::atomic<int> next{0}, running{0}, overlapped{0};
    int first_at = -1, second_at = -1;
    const auto task = [&](int& at) {
      if (++running > 1) ++overlapped;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      at = next++;
      --running;
    };
    run_side_by_side(faces, [&] { task(first_at); }, [&] { task(second_at); });
    EXPECT_EQ(next.load(), 2) << faces;  // both ran
    if (faces >= kSideBySideFaces) {
      EXPECT_EQ(first_at, 0);
      EXPECT_EQ(second_at, 1);
      EXPECT_EQ(overlapped.load(), 0);
    }
  }
}

// Inside a branch of a pair run side by side, an inner pair runs in order on the branch's thread (both cores are
// busy with the outer pair); after the outer pair, pairs run side by side again.
TEST(SideBySide, APairInsideAPairRunsInOrder) {
  std::atomic<int> inner_overlaps{0};
  const auto inner_pair = [&] {
    const std::thread::id here = std::this_thread::get_id();
    std::atomic<int> running{0};
    int order = 0, first_at = -1, second_at = -1;
    bool same_thread = true;
    const auto task = [&](int& at) {
      if (++running > 1) ++inner_overlaps;
      same_thread = same_thread && std::this_thread::get_id() == here;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      at = order++;
      --running;
    };
    run_side_by_side(
        10, [&] { task(first_at); }, [&] { task(second_at); });
    EXPECT_TRUE(same_thread);
    EXPECT_EQ(first_at, 0);
    EXPECT_EQ(second_at, 1);
  };
  run_side_by_side(10, inner_pair, inner_pair);
  EXPECT_EQ(inner_overlaps.load(), 0);
  EXPECT_EQ(detail::side_by_side_depth, 0);  // left as it was, also on this thread
}

TEST(SideBySide, TheFirstTasksErrorWinsWhenBothThrowAndBothStillRun) {
  for (const int faces : {10, kSideBySideFaces}) {
    std::atomic<int> finished{0};
    try {
      run_side_by_side(
          faces, [&] { ++finished; throw std::runtime_error("first"); },
          [&] { ++finished; throw std::runtime_error("second"); });
      ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "first") << faces;
    }
    // Sequentially the second never starts after the first threw; side by side both ran.
    EXPECT_EQ(finished.load(), faces < kSideBySideFaces ? 2 : 1) << faces;
  }
  EXPECT_THROW(run_side_by_side(10, [] {}, [] { throw std::logic_error("second"); }), std::logic_error);
}

/// Counts reports without any locking of its own, and answers with fixed values.
class CountingSink final : public ProgressSink {
 public:
  void report(std::string_view, double, std::string_view message) override {
    const int before = reports;
    std::this_thread::yield();  // widens the window in which an unserialized second caller would be lost
    reports = before + 1;
    last = std::string(message);
  }
  bool cancelled() const override { return false; }
  bool skip_improvements() const override { return true; }
  double seconds_left() const override { return 7.5; }
  int reports = 0;
  std::string last;
};

TEST(SerializedProgress, ForwardsEveryCallAndLosesNoReportOfTwoThreads) {
  CountingSink inner;
  SerializedProgress shared(inner);
  EXPECT_FALSE(shared.cancelled());
  EXPECT_TRUE(shared.skip_improvements());
  EXPECT_EQ(shared.seconds_left(), 7.5);
  constexpr int kEach = 2000;
  std::thread a([&] {
    for (int i = 0; i < kEach; ++i) shared.report("s", 0.5, "a");
  });
  std::thread b([&] {
    for (int i = 0; i < kEach; ++i) shared.report("s", 0.5, "b");
  });
  a.join();
  b.join();
  EXPECT_EQ(inner.reports, 2 * kEach);
  EXPECT_TRUE(inner.last == "a" || inner.last == "b");
}

}  // namespace
}  // namespace quadcover
