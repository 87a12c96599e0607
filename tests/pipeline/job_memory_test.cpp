// The report's "memory" section (pipeline/job_report.h): per-stage peak resident bytes under the names of
// "seconds", in pipeline order, below the process peak.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "common/memory.h"

#include "pipeline/job_report.h"
#include "pipeline/remesh_mesh.h"
#include "support/report_memory.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

TEST(JobMemory, RemeshReportHasAPeakForEveryTimedStage) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  const RemeshJob job = remesh_mesh(mesh, PipelineOptions{});
  ASSERT_EQ(job.param.peak_bytes.size(), job.param.seconds.size());
  for (std::size_t i = 0; i < job.param.seconds.size(); ++i)
    EXPECT_EQ(job.param.peak_bytes[i].first, job.param.seconds[i].first);  // measured at the same points
  const nlohmann::json r = remesh_report(mesh, job);
  testing::expect_memory_matches_seconds(r);
  EXPECT_EQ(r["memory"]["input_faces"], mesh.num_faces());
  // In pipeline order, with the parameterization's steps and the report's own metrics.
  const std::vector<std::string> order = {"field",   "optimize", "keep_better",   "param_cut", "param_assemble",
                                          "extract", "smooth",   "surface_check", "metrics"};
  for (std::size_t i = 0; i + 1 < order.size(); ++i) {
    EXPECT_GE(testing::memory_stage_index(r, order[i]), 0) << order[i];
    EXPECT_LT(testing::memory_stage_index(r, order[i]), testing::memory_stage_index(r, order[i + 1])) << order[i];
  }
}

// A stage added after the report (the CLI's writing) joins both sections, and the process peak follows a stage that
// raised it.
TEST(JobMemory, AddedStageJoinsSecondsAndMemoryAndRaisesTheProcessPeak) {
  const Mesh mesh = testing::make_torus(30, 12);
  PipelineOptions options;
  options.param.density.target_quads = 300;
  nlohmann::json r = remesh_report(mesh, remesh_mesh(mesh, options));
  const std::int64_t peak_before = r["memory"]["peak_bytes"].get<std::int64_t>();
  const std::size_t stages_before = r["memory"]["stages"].size();
  StageMeter meter;
  // A block that takes the resident size 32 MB above the peak so far, every page touched.
  const std::int64_t extra = std::max<std::int64_t>(0, peak_before - resident_bytes()) + (32 << 20);
  std::vector<char> block(static_cast<std::size_t>(extra), 1);
  add_report_stage(r, "write", meter.lap());
  EXPECT_EQ(block[block.size() / 2], 1);
  ASSERT_EQ(r["memory"]["stages"].size(), stages_before + 1);
  EXPECT_EQ(testing::memory_stage_index(r, "write"), static_cast<int>(stages_before));
  EXPECT_TRUE(r["seconds"].contains("write"));
  testing::expect_memory_matches_seconds(r);
#ifdef __linux__
  EXPECT_GE(r["memory"]["stages"].back()["peak_bytes"].get<std::int64_t>(), peak_before + (16 << 20));
  EXPECT_GE(r["memory"]["peak_bytes"].get<std::int64_t>(), peak_before + (16 << 20));
#endif
}

}  // namespace
}  // namespace quadcover
