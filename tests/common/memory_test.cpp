// Resident memory helpers (common/memory.h): plausible values, a reset peak that sees a later allocation, and
// nested stages whose resets keep the outer stage's and the process's peaks.
#include "common/memory.h"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>

namespace quadcover {
namespace {

TEST(Memory, PeakIsAtLeastTheCurrentResidentSize) {
  const std::int64_t now = resident_bytes(), peak = peak_resident_bytes();
#ifdef __linux__
  EXPECT_GT(now, 0);
#endif
  EXPECT_GE(peak, now);
}

TEST(Memory, ResetPeakThenAllocationRaisesIt) {
  if (!reset_peak_resident()) GTEST_SKIP() << "the kernel refused to reset VmHWM";
  const StagePeakMemory stage;
  const std::int64_t before = stage.peak();
  constexpr std::size_t kBytes = 64 << 20;
  auto block = std::make_unique<char[]>(kBytes);
  std::memset(block.get(), 1, kBytes);  // touch every page
  EXPECT_GE(stage.peak(), before + static_cast<std::int64_t>(kBytes) / 2);
  const char sum = block[kBytes / 2];
  block.reset();
  EXPECT_EQ(sum, 1);
  // After freeing, a new reset brings the peak back below the stage's.
  const std::int64_t stage_peak = stage.peak();
  ASSERT_TRUE(reset_peak_resident());
  EXPECT_LT(peak_resident_bytes(), stage_peak);
}

/// Allocates `bytes`, touches every page and frees them again.
void touch_and_free(std::size_t bytes) {
  auto block = std::make_unique<char[]>(bytes);
  std::memset(block.get(), 1, bytes);
  EXPECT_EQ(block[bytes / 2], 1);
}

TEST(Memory, InnerStageResetsKeepTheOuterAndProcessPeaks) {
  if (!reset_peak_resident()) GTEST_SKIP() << "the kernel refused to reset VmHWM";
  constexpr std::int64_t kBytes = 64 << 20;
  StagePeakMemory outer;
  const std::int64_t start = outer.peak();
  {
    const StagePeakMemory inner;
    touch_and_free(kBytes);
    EXPECT_GE(inner.peak(), start + kBytes / 2);
  }
  StagePeakMemory later;  // its reset clears the VmHWM the block raised
  EXPECT_LT(peak_resident_bytes(), start + kBytes / 2);
  EXPECT_LT(later.peak(), start + kBytes / 2);
  EXPECT_GE(outer.peak(), start + kBytes / 2);
  EXPECT_GE(process_peak_resident_bytes(), outer.peak());
  // restart() forgets the stage's own peak.
  outer.restart();
  EXPECT_LT(outer.peak(), start + kBytes / 2);
  EXPECT_GE(process_peak_resident_bytes(), start + kBytes / 2);
}

}  // namespace
}  // namespace quadcover
