// Resident memory helpers (common/memory.h): plausible values, and a reset peak that sees a later allocation.
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

}  // namespace
}  // namespace quadcover
