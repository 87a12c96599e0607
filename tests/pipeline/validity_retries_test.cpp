// Validity retries (pipeline/validity_retries.h, retry_until_valid.h): the density sequence, the order of
// Validity, the loop on a stub job whose validity is a table of the density, and a real remesh whose thin handle no
// nearby density resolves (every attempt reported, a warning, never a silent change of topology).
#include "pipeline/validity_retries.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "param/seams.h"
#include "pipeline/memory_budget.h"
#include "pipeline/remesh_mesh.h"
#include "pipeline/retry_until_valid.h"
#include "support/angle_sums.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

// Steps of 4 % at the default density; of 2 % when the user asked for a density, so that the default single retry
// stays within ±3 % of a requested quad count.
TEST(ValidityRetries, DensitiesAlternateAroundTheFirstInStepsOfFourOrTwoPercent) {
  const double by_default[] = {1.0, 1.04, 0.96, 1.08, 0.92, 1.12};
  const double requested[] = {1.0, 1.02, 0.98, 1.04, 0.96, 1.06};
  DensityOptions count, length;
  count.target_quads = 500;
  length.edge_length = 0.1;
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(attempt_quads_factor(k, DensityOptions{}), by_default[k], 1e-12) << k;
    EXPECT_NEAR(attempt_quads_factor(k, count), requested[k], 1e-12) << k;
    EXPECT_NEAR(attempt_quads_factor(k, length), requested[k], 1e-12) << k;
  }
}

TEST(ValidityRetries, AttemptOptionsScaleTheRequestedCountOrTheFirstEdgeLength) {
  PipelineOptions count;
  count.param.density.target_quads = 1000;
  count.validity_retries = 3;
  EXPECT_EQ(attempt_options(count, 0.5, 1).param.density.target_quads, 1020);
  EXPECT_EQ(attempt_options(count, 0.5, 2).param.density.target_quads, 980);
  EXPECT_EQ(attempt_options(count, 0.5, 2).param.density.edge_length, 0.0);
  EXPECT_EQ(attempt_options(count, 0.5, 2).validity_retries, 0);
  const PipelineOptions by_default;  // the default density: attempt 0's h is the reference
  const PipelineOptions finer = attempt_options(by_default, 0.1, 1);
  EXPECT_NEAR(finer.param.density.edge_length, 0.1 / std::sqrt(1.04), 1e-15);
  EXPECT_EQ(finer.param.density.target_quads, 0);
  EXPECT_NO_THROW(validate(finer));
  // The default made explicit is still the job's own density (components get theirs), a length given is the user's.
  EXPECT_TRUE(finer.param.density.edge_length_from_default);
  PipelineOptions length;
  length.param.density.edge_length = 0.2;
  EXPECT_FALSE(attempt_options(length, 0.2, 1).param.density.edge_length_from_default);
}

TEST(ValidityRetries, TopologyComesFirstThenFoldsThenWindingsThenNonQuads) {
  auto v = [](int topology, int folds, int windings, int non_quads) {
    Validity x;
    x.topology_changes = topology, x.non_positive = folds, x.wrong_windings = windings, x.non_quads = non_quads;
    return x;
  };
  EXPECT_LT(v(0, 9, 9, 9), v(1, 0, 0, 0));
  EXPECT_LT(v(0, 0, 9, 9), v(0, 1, 0, 0));
  EXPECT_LT(v(0, 0, 0, 9), v(0, 0, 1, 0));
  EXPECT_LT(v(0, 0, 0, 1), v(0, 0, 0, 2));
  EXPECT_TRUE(v(0, 0, 0, 5).valid());
  EXPECT_FALSE(v(0, 0, 1, 0).valid());
  EXPECT_FALSE(v(0, 0, 1, 0).worth_retrying());
  EXPECT_TRUE(v(0, 1, 0, 0).worth_retrying());
  EXPECT_TRUE(v(1, 0, 0, 0).worth_retrying());
}

/// A job that only knows its density; its validity is looked up by the density factor.
struct StubJob {
  ParamJob param;
};
ParamJob& param_job(StubJob& job) { return job.param; }

struct StubRuns {
  std::map<long, Validity> by_factor;  // key: round(1000 · factor)
  int runs = 0;
  StubJob run(const PipelineOptions& o) {
    ++runs;
    StubJob job;
    job.param.options = o;
    job.param.map.edge_length = o.param.density.edge_length;
    return job;
  }
  Validity judge(const StubJob& job, double h0) const {
    const double factor = std::pow(h0 / job.param.map.edge_length, 2);
    return by_factor.at(std::lround(1000 * factor));
  }
};

Validity folds(int n) {
  Validity v;
  v.non_positive = n;
  return v;
}

StubJob run_stub(StubRuns& stub, int retries, ProgressSink& progress = null_progress()) {
  PipelineOptions given;
  given.optimize = OptimizeMode::None;  // the density retries alone (the full optimization's fallback: OptimizeStub)
  given.validity_retries = retries;
  given.param.density.edge_length = 0.2;
  return retry_until_valid(
      given, [&](const PipelineOptions& o) { return stub.run(o); },
      [&](const StubJob& job) { return stub.judge(job, 0.2); }, progress);
}

TEST(ValidityRetries, StopsAtTheFirstValidAttemptAndSaysWhichWasKept) {
  StubRuns stub;
  stub.by_factor = {{1000, folds(3)}, {1020, folds(1)}, {980, folds(0)}, {1040, folds(0)}};
  const StubJob job = run_stub(stub, 4);
  EXPECT_EQ(stub.runs, 3);  // 1.0, 1.02, 0.98: the third is valid, 1.04 never runs
  ASSERT_EQ(job.param.validity_attempts.size(), 3u);
  EXPECT_EQ(job.param.validity_attempt_used, 2);
  EXPECT_EQ(job.param.validity_attempts[1].validity.non_positive, 1);
  EXPECT_NEAR(job.param.validity_attempts[2].quads_factor, 0.98, 1e-12);
  EXPECT_NEAR(job.param.map.edge_length, 0.2 / std::sqrt(0.98), 1e-12);
  ASSERT_EQ(job.param.warnings.size(), 1u);
  EXPECT_NE(job.param.warnings[0].find("3 non-positive triangles"), std::string::npos) << job.param.warnings[0];
  EXPECT_NE(job.param.warnings[0].find("retried at +2% quads, at -2% quads and kept a valid result, at -2% quads"),
            std::string::npos)
      << job.param.warnings[0];
}

TEST(ValidityRetries, WithoutAValidAttemptTheBestIsKeptAndItsDefectsAreSaid) {
  StubRuns stub;
  stub.by_factor = {{1000, folds(3)}, {1020, folds(1)}};
  const StubJob job = run_stub(stub, 1);
  EXPECT_EQ(stub.runs, 2);
  EXPECT_EQ(job.param.validity_attempt_used, 1);
  ASSERT_EQ(job.param.warnings.size(), 1u);
  EXPECT_NE(job.param.warnings[0].find("kept the best, with 1 non-positive triangles"), std::string::npos)
      << job.param.warnings[0];
}

// A first attempt whose default density was made finer for a short loop (param/density.h): the retries run at
// explicit densities around it, and the one kept still says why its density is that fine.
TEST(ValidityRetries, ADensityMadeFinerForALoopIsKeptAndSaidByTheRetries) {
  StubRuns stub;
  stub.by_factor = {{1000, folds(3)}, {1020, folds(0)}};
  PipelineOptions given;
  given.optimize = OptimizeMode::None;
  given.validity_retries = 2;
  given.param.density.edge_length = 0.2;
  LoopDensityRaise raise;
  raise.loop = 3, raise.vertex = 17, raise.length = 0.4, raise.quads_factor = 5.0, raise.grid_units = 4;
  const StubJob job = retry_until_valid(
      given,
      [&](const PipelineOptions& o) {
        StubJob j = stub.run(o);
        if (stub.runs == 1) j.param.density.raised = raise;  // only the first attempt fixes the default density
        return j;
      },
      [&](const StubJob& j) { return stub.judge(j, 0.2); }, null_progress());
  ASSERT_EQ(job.param.validity_attempt_used, 1);
  EXPECT_EQ(job.param.density.raised.loop, 3);
  EXPECT_EQ(job.param.density.raised.quads_factor, 5.0);
  ASSERT_EQ(job.param.warnings.size(), 2u);
  EXPECT_EQ(job.param.warnings[0], loop_density_warning(raise));
  EXPECT_NE(job.param.warnings[0].find("made 5.0 times finer (quads) so that boundary loop 3 (through vertex 17 at"),
            std::string::npos)
      << job.param.warnings[0];
  EXPECT_NE(job.param.warnings[1].find("kept a valid result"), std::string::npos) << job.param.warnings[1];
}

// The warning of a default density made finer says how many times more quads the kept h gives than the first
// attempt's: 4 per halving of the edge factor, less when the branch points' bound held the default h finer already.
TEST(ValidityRetries, TheFinerDensityWarningSaysTheFactorOfTheKeptEdgeLength) {
  const auto said = [](double first_h, double kept_h, int halvings) {
    ParamJob job;
    job.map.edge_length = kept_h;
    say_made_finer(job, halvings, first_h);
    return job.warnings.empty() ? std::string() : job.warnings.front();
  };
  EXPECT_NE(said(0.2, 0.1, 1).find("made 4 times finer, h = 0.100000"), std::string::npos);
  EXPECT_NE(said(0.0989, 0.0615, 2).find("made 2.59 times finer"), std::string::npos);
  EXPECT_NE(said(0, 0.05, 2).find("made 16 times finer"), std::string::npos);  // attempt 0 gave no map
  EXPECT_EQ(said(0.1, 0.1, 2), "");                                            // nothing was made finer
  EXPECT_EQ(said(0.2, 0.1, 0), "");
}

TEST(ValidityRetries, AValidFirstAttemptRunsOnceWithoutAWarning) {
  StubRuns stub;
  stub.by_factor = {{1000, folds(0)}};
  const StubJob job = run_stub(stub, 3);
  EXPECT_EQ(stub.runs, 1);
  EXPECT_EQ(job.param.validity_attempts.size(), 1u);
  EXPECT_TRUE(job.param.warnings.empty());
}

TEST(ValidityRetries, WrongWindingsAloneAreSaidButNotRetried) {
  StubRuns stub;
  Validity wound;
  wound.wrong_windings = 2;
  stub.by_factor = {{1000, wound}};
  const StubJob job = run_stub(stub, 3);
  EXPECT_EQ(stub.runs, 1);
  ASSERT_EQ(job.param.warnings.size(), 1u);
  EXPECT_NE(job.param.warnings[0].find("2 vertices wound other than the field"), std::string::npos);
  EXPECT_NE(job.param.warnings[0].find("not retried"), std::string::npos);
}

/// A job whose validity depends only on its field: FieldStyle::Auto resolves to Smooth (a closed surface).
struct FieldStub {
  Validity smooth, curvature;
  std::vector<FieldStyle> runs;
  bool curvature_refused = false;  // its run throws, as for a density too coarse for that field
  StubJob run(const PipelineOptions& o) {
    if (curvature_refused && o.field_style == FieldStyle::Curvature) throw InputError("density", 0, "refused");
    StubJob job;
    job.param.options = o;
    if (o.field_style == FieldStyle::Auto) job.param.options.field_style = FieldStyle::Smooth;
    job.param.map.edge_length = 0.2;
    runs.push_back(job.param.options.field_style);
    return job;
  }
  StubJob kept(FieldStyle given_style) {
    PipelineOptions given;
    given.optimize = OptimizeMode::None;  // the field's fallback alone
    given.field_style = given_style;
    given.param.density.edge_length = 0.2;
    return retry_until_valid(
        given, [&](const PipelineOptions& o) { return run(o); },
        [&](const StubJob& job) { return job.param.options.field_style == FieldStyle::Smooth ? smooth : curvature; },
        null_progress());
  }
};

Validity wound(int n) {
  Validity v;
  v.wrong_windings = n;
  return v;
}

TEST(ValidityRetries, AutoFallsBackToTheCurvatureFieldOnlyWhenTheSmoothOneIsNotValid) {
  FieldStub stub{wound(8), wound(2), {}, false};  // wrong windings: no density retry after the field's
  StubJob job = stub.kept(FieldStyle::Auto);
  EXPECT_EQ(stub.runs, (std::vector{FieldStyle::Smooth, FieldStyle::Curvature}));
  EXPECT_EQ(job.param.validity_attempt_used, 1);
  EXPECT_EQ(job.param.options.field_style, FieldStyle::Curvature);
  EXPECT_TRUE(job.param.field_style_auto);
  ASSERT_EQ(job.param.warnings.size(), 1u);
  EXPECT_NE(job.param.warnings[0].find("retried using the curvature field and kept the best, with 0 non-positive "
                                       "triangles, 2 vertices wound other than the field, using the curvature field"),
            std::string::npos)
      << job.param.warnings[0];
  FieldStub tie{wound(2), wound(2), {}, false};  // not more valid: the smoothest field's map stays
  job = tie.kept(FieldStyle::Auto);
  EXPECT_EQ(tie.runs.size(), 2u);
  EXPECT_EQ(job.param.validity_attempt_used, 0);
  EXPECT_EQ(job.param.options.field_style, FieldStyle::Smooth);
  FieldStub valid{Validity{}, wound(2), {}, false};
  job = valid.kept(FieldStyle::Auto);
  EXPECT_EQ(valid.runs, (std::vector{FieldStyle::Smooth}));
  EXPECT_TRUE(job.param.warnings.empty());
  FieldStub refused{wound(8), wound(2), {}, true};  // the fallback fails: the smooth result stays, and it is said
  job = refused.kept(FieldStyle::Auto);
  EXPECT_EQ(job.param.options.field_style, FieldStyle::Smooth);
  EXPECT_EQ(job.param.validity_attempts.size(), 1u);
  ASSERT_EQ(job.param.warnings.size(), 2u);
  EXPECT_NE(job.param.warnings[0].find("curvature-guided field, tried because this one is not valid, could not be "
                                       "made: "),
            std::string::npos)
      << job.param.warnings[0];
  FieldStub chosen{wound(8), wound(2), {}, false};  // a style the user chose is kept
  job = chosen.kept(FieldStyle::Smooth);
  EXPECT_EQ(chosen.runs, (std::vector{FieldStyle::Smooth}));
  EXPECT_FALSE(job.param.field_style_auto);
}

/// A job whose validity depends only on Algorithm 6.1's mode, on a map of `faces` triangles.
struct OptimizeStub {
  Validity relocate, full;
  long faces = 1000;
  std::vector<OptimizeMode> runs;
  StubJob run(const PipelineOptions& o) {
    StubJob job;
    job.param.options = o;
    job.param.options.field_style = FieldStyle::Curvature;
    job.param.map.edge_length = 0.2;
    job.param.map.uv.resize(faces, 3);
    runs.push_back(o.optimize);
    return job;
  }
  StubJob kept(OptimizeMode mode) {
    PipelineOptions given;
    given.optimize = mode;
    given.field_style = FieldStyle::Curvature;
    given.param.density.edge_length = 0.2;
    return retry_until_valid(
        given, [&](const PipelineOptions& o) { return run(o); },
        [&](const StubJob& job) { return job.param.options.optimize == OptimizeMode::Full ? full : relocate; },
        null_progress());
  }
};

TEST(ValidityRetries, ANotValidRelocatedMapIsMadeAgainWithTheFullOptimizationOnSmallMeshes) {
  OptimizeStub stub{wound(2), Validity{}, 1000, {}};
  StubJob job = stub.kept(OptimizeMode::Relocate);
  EXPECT_EQ(stub.runs, (std::vector{OptimizeMode::Relocate, OptimizeMode::Full}));
  EXPECT_EQ(job.param.validity_attempt_used, 1);
  EXPECT_EQ(job.param.options.optimize, OptimizeMode::Full);
  ASSERT_EQ(job.param.validity_attempts.size(), 2u);
  EXPECT_EQ(job.param.validity_attempts[0].optimize, OptimizeMode::Relocate);
  EXPECT_EQ(job.param.validity_attempts[1].optimize, OptimizeMode::Full);
  ASSERT_EQ(job.param.warnings.size(), 1u);
  EXPECT_NE(job.param.warnings[0].find("retried using the full optimization and kept a valid result, using the full "
                                       "optimization"),
            std::string::npos)
      << job.param.warnings[0];
  OptimizeStub worse{wound(2), wound(3), 1000, {}};  // not more valid: relocate's map stays
  job = worse.kept(OptimizeMode::Relocate);
  EXPECT_EQ(worse.runs.size(), 2u);
  EXPECT_EQ(job.param.validity_attempt_used, 0);
  EXPECT_EQ(job.param.options.optimize, OptimizeMode::Relocate);
  OptimizeStub valid{Validity{}, wound(2), 1000, {}};  // a valid map: once
  job = valid.kept(OptimizeMode::Relocate);
  EXPECT_EQ(valid.runs.size(), 1u);
  EXPECT_TRUE(job.param.warnings.empty());
  OptimizeStub large{wound(2), Validity{}, kFullFallbackMaxFaces + 1, {}};  // above the size it is tried on
  job = large.kept(OptimizeMode::Relocate);
  EXPECT_EQ(large.runs.size(), 1u);
  for (const OptimizeMode chosen : {OptimizeMode::None, OptimizeMode::Full}) {  // other modes: as they are
    OptimizeStub other{wound(2), wound(2), 1000, {}};
    job = other.kept(chosen);
    EXPECT_EQ(other.runs, (std::vector{chosen}));
  }
}

/// A job whose validity depends only on whether its field followed crisp short creases, of which the mesh has
/// `crisp_edges` (FeatureOptions::crisp_crease_degrees).
struct CreaseStub {
  Validity crisp, chains;
  int crisp_edges = 40;
  std::vector<bool> runs;  // per run: crisp creases on
  StubJob run(const PipelineOptions& o) {
    StubJob job;
    job.param.options = o;
    job.param.options.field_style = FieldStyle::Curvature;
    job.param.map.edge_length = 0.2;
    const bool on = o.param.features.crisp_crease_degrees > 0;
    job.param.crisp_creases = on ? crisp_edges : 0;
    runs.push_back(on);
    return job;
  }
  StubJob kept() {
    PipelineOptions given;
    given.optimize = OptimizeMode::None;  // no fallback to the full optimization
    given.field_style = FieldStyle::Curvature;
    given.param.density.edge_length = 0.2;
    return retry_until_valid(
        given, [&](const PipelineOptions& o) { return run(o); },
        [&](const StubJob& job) { return job.param.options.param.features.crisp_crease_degrees > 0 ? crisp : chains; },
        null_progress());
  }
};

// A map not valid with the crisp short creases followed is made again following the long chains alone, kept when
// more valid and said; not when the mesh has no such crease, nor when the map is valid.
TEST(ValidityRetries, ANotValidMapWithCrispCreasesIsMadeAgainFollowingTheLongChainsAlone) {
  CreaseStub stub{wound(20), Validity{}, 40, {}};
  StubJob job = stub.kept();
  EXPECT_EQ(stub.runs, (std::vector{true, false}));
  EXPECT_EQ(job.param.validity_attempt_used, 1);
  EXPECT_EQ(job.param.options.param.features.crisp_crease_degrees, 0);
  ASSERT_EQ(job.param.validity_attempts.size(), 2u);
  EXPECT_TRUE(job.param.validity_attempts[0].crisp_creases);
  EXPECT_FALSE(job.param.validity_attempts[1].crisp_creases);
  ASSERT_EQ(job.param.warnings.size(), 1u);
  EXPECT_NE(job.param.warnings[0].find("retried using the long crease chains alone as features and kept a valid "
                                       "result"),
            std::string::npos)
      << job.param.warnings[0];
  CreaseStub worse{wound(2), wound(3), 40, {}};  // not more valid: the crisp creases' map stays
  job = worse.kept();
  EXPECT_EQ(worse.runs.size(), 2u);
  EXPECT_EQ(job.param.validity_attempt_used, 0);
  EXPECT_GT(job.param.options.param.features.crisp_crease_degrees, 0);
  CreaseStub none{wound(2), Validity{}, 0, {}};  // no crisp crease followed: nothing to drop
  none.kept();
  EXPECT_EQ(none.runs, (std::vector{true}));
  CreaseStub valid{Validity{}, wound(2), 40, {}};
  job = valid.kept();
  EXPECT_EQ(valid.runs, (std::vector{true}));
  EXPECT_TRUE(job.param.warnings.empty());
}

/// A sink past its time limit: the improving stages are skipped.
struct PastLimit : ProgressSink {
  void report(std::string_view, double, std::string_view) override {}
  bool skip_improvements() const override { return true; }
};

TEST(ValidityRetries, APassedTimeLimitSkipsTheRetriesAndRecordsItAsCutShort) {
  StubRuns stub;
  stub.by_factor = {{1000, folds(2)}};
  PastLimit past;
  const StubJob job = run_stub(stub, 2, past);
  EXPECT_EQ(stub.runs, 1);
  ASSERT_EQ(job.param.cut_short.size(), 1u);
  EXPECT_EQ(job.param.cut_short[0], "validity retries");
}

TEST(ValidityRetries, AHandleThinnerThanTheQuadsIsRetriedReportedAndNeverSilent) {
  // A torus whose tube (circumference 0.5) is under three quad edges at 100 quads: no density nearby keeps it.
  const Mesh torus = testing::make_torus(24, 6, 1.0, 0.08);
  PipelineOptions options;
  options.param.density.target_quads = 100;
  options.validity_retries = 2;
  const RemeshJob job = remesh_mesh(torus, options);
  const auto& attempts = job.param.validity_attempts;
  // The default field style on a closed surface: the smoothest field first, then its fallback to the curvature-
  // guided one (fall_back_to_curvature), the full optimization's (fall_back_to_full_optimization), then the two
  // density retries with the field and optimization of the best of those.
  ASSERT_EQ(attempts.size(), 5u);
  EXPECT_EQ(attempts[0].field_style, FieldStyle::Smooth);
  EXPECT_EQ(attempts[1].field_style, FieldStyle::Curvature);
  EXPECT_EQ(attempts[0].optimize, OptimizeMode::Relocate);
  EXPECT_EQ(attempts[1].optimize, OptimizeMode::Relocate);
  EXPECT_EQ(attempts[2].optimize, OptimizeMode::Full);
  EXPECT_EQ(attempts[3].field_style, attempts[4].field_style);
  EXPECT_EQ(attempts[3].optimize, attempts[4].optimize);
  EXPECT_TRUE(job.param.field_style_auto);
  EXPECT_EQ(job.param.options.field_style,
            attempts[static_cast<std::size_t>(job.param.validity_attempt_used)].field_style);
  for (const ValidityAttempt& a : attempts) EXPECT_EQ(a.validity.topology_changes, 1);
  for (const ValidityAttempt& a : attempts) EXPECT_GT(a.seconds, 0.0);  // each attempt's own wall time
  EXPECT_FALSE(job.surface.same_topology);
  // The kept attempt's numbers are the job's own, recounted.
  const Validity& kept = attempts[static_cast<std::size_t>(job.param.validity_attempt_used)].validity;
  EXPECT_EQ(kept.non_positive, flipped_triangles(job.param.mesh(torus), job.param.map.uv).non_positive);
  EXPECT_EQ(kept.non_quads, job.surface.output.non_quads);
  bool said = false;
  for (const std::string& w : job.param.warnings)
    said = said || w.find("the quad mesh's topology changed") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(ValidityRetries, ACleanMapHasNoWrongWindingAndItsBranchPointsAreTheField) {
  const Mesh torus = testing::make_torus(40, 16);
  PipelineOptions options;
  options.param.density.target_quads = 400;
  const ParamJob job = parameterize_mesh(torus, options);
  EXPECT_EQ(job.validity_attempts.size(), 1u);
  EXPECT_TRUE(wrong_winding_vertices(job.mesh(torus), job.map).empty());
  EXPECT_TRUE(map_validity(job.mesh(torus), job.map).valid());
}

TEST(ValidityRetries, AVertexMovedOutOfItsRingWindsZeroTimesAndIsFound) {
  const Mesh torus = testing::make_torus(40, 16);
  PipelineOptions options;
  options.param.density.target_quads = 400;
  ParamJob job = parameterize_mesh(torus, options);
  const Mesh& mesh = job.mesh(torus);
  int p = 0;  // an interior vertex that is not a branch point, with every corner in one chart
  for (const BranchPoint& b : job.map.branch_points) ASSERT_NE(b.vertex, p);
  // Move φ(p) by ten grid units in every corner of p: its ring no longer surrounds it, the angle sum is ~0.
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int c = 0; c < 3; ++c)
      if (mesh.F()(f, c) == p) job.map.uv(f, c) += Complex(10.0, 0.0);
  // Direct recomputation from the corner angles, against the field's index (0 but at the branch points; closed).
  const Eigen::VectorXi wound = testing::quarter_index_by_angle_sums(mesh, job.map.uv);
  std::vector<int> target(static_cast<std::size_t>(mesh.num_vertices()), 0), expected;
  for (const BranchPoint& b : job.map.branch_points) target[b.vertex] = b.quarter_index;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (wound[v] != target[v]) expected.push_back(v);
  const std::vector<int> wrong = wrong_winding_vertices(mesh, job.map);
  EXPECT_EQ(wrong, expected);
  EXPECT_NE(std::find(wrong.begin(), wrong.end(), p), wrong.end());
  EXPECT_GT(map_validity(mesh, job.map).non_positive, 0);
}

}  // namespace
}  // namespace quadcover

namespace quadcover {
namespace {

/// The aligned curves of `map` that are enforced, and those freed at wrong windings.
std::pair<int, int> enforced_and_freed(const Parameterization& map) {
  int enforced = 0, freed = 0;
  for (const Parameterization::Curve& c : map.aligned_curves) {
    enforced += c.enforced ? 1 : 0;
    freed += c.left_free_because.rfind("freed", 0) == 0 ? 1 : 0;
  }
  return {enforced, freed};
}

// Rounding the curves with the periods (param/curve_rounding.h, --round-curves) pins every crease of fandisk; that map
// winds wrongly beside a few cones, so the job frees the curves there and keeps the others pinned: valid, with more
// curves on iso-lines than the period-matrix rounding alone. cow's curves leave more wrong windings even when freed,
// so the job falls back to the period-matrix map and says so (with its close opposite cone pairs kept: cancelled,
// they leave none); lilium_disk's boundary loop needs neither. The result is never less valid than without the
// option.
TEST(CurveRoundingFallback, FreesTheCurvesAtWrongWindingsAndFallsBackOnlyWhenStillWorse) {
  for (const char* name : {"fandisk", "cow", "lilium_disk"}) {
    SCOPED_TRACE(name);
    const Mesh mesh = testing::load_test_mesh(name);
    PipelineOptions plain;
    plain.field_style = FieldStyle::Curvature;  // the field of the cases above
    plain.validity_retries = 0;
    plain.cancel_close_cones = false;
    PipelineOptions rounding = plain;
    rounding.param.alignment.round_with_periods = true;
    const ParamJob a = parameterize_mesh(mesh, plain);
    const ParamJob b = parameterize_mesh(mesh, rounding);
    const Validity va = map_validity(a.mesh(mesh), a.map), vb = map_validity(b.mesh(mesh), b.map);
    EXPECT_FALSE(va < vb);  // never less valid
    const bool dropped = b.map.diagnostics.rounding.curve_rounding_dropped;
    EXPECT_EQ(dropped, !b.options.param.alignment.round_with_periods);
    EXPECT_EQ(b.map.diagnostics.rounding.curve_lines > 0, !dropped);
    const auto [enforced_a, freed_a] = enforced_and_freed(a.map);
    const auto [enforced_b, freed_b] = enforced_and_freed(b.map);
    EXPECT_EQ(freed_a, 0);
    auto ran = [&](const char* stage) {
      return std::any_of(b.seconds.begin(), b.seconds.end(), [&](const auto& s) { return s.first == stage; });
    };
    if (std::string(name) == "cow") {
      EXPECT_TRUE(dropped);
      EXPECT_TRUE(ran("curve_freeing"));
      EXPECT_TRUE(ran("curve_rounding_fallback"));
      continue;
    }
    EXPECT_FALSE(dropped);
    EXPECT_TRUE(vb.valid());
    EXPECT_GT(enforced_b, enforced_a);
    const bool fandisk = std::string(name) == "fandisk";
    EXPECT_EQ(freed_b > 0, fandisk);
    EXPECT_EQ(!b.options.param.alignment.free_line_vertices.empty(), fandisk);
    EXPECT_EQ(ran("curve_freeing"), fandisk);
    EXPECT_FALSE(ran("curve_rounding_fallback"));
  }
}

// A tube thinner than the default quad edge (h = 2 × the mean edge length, here 0.15 against a circumference of
// 0.13) folds most of the map: the default density is halved until the map holds it, the result keeps the torus,
// and a warning says so. The same h given by the user is kept as given; a coarse triangulation of a round shape is
// not made finer.
TEST(ValidityRetries, ATubeThinnerThanTheDefaultQuadEdgeIsMadeFinerAndKeepsItsTopology) {
  const Mesh tube = testing::make_torus(60, 6, 1.0, 0.02);
  const double default_h = 2 * tube.mean_edge_length();
  const auto warned = [](const ParamJob& job) {
    return std::any_of(job.warnings.begin(), job.warnings.end(), [](const std::string& w) {
      return w.find("the default density was too coarse for this shape") != std::string::npos;
    });
  };
  const RemeshJob job = remesh_mesh(tube, PipelineOptions{});
  EXPECT_TRUE(job.surface.same_topology);
  EXPECT_EQ(job.surface.output.non_quads, 0);
  EXPECT_EQ(flipped_triangles(job.param.mesh(tube), job.param.map.uv).non_positive, 0);
  EXPECT_LT(job.param.map.edge_length, default_h / 2);
  EXPECT_TRUE(warned(job.param));
  EXPECT_LT(job.param.options.param.density.default_edge_factor, DensityOptions{}.default_edge_factor / 2);
  PipelineOptions given;
  given.param.density.edge_length = default_h;
  given.validity_retries = 0;
  const ParamJob as_given = parameterize_mesh(tube, given);
  EXPECT_EQ(as_given.map.edge_length, default_h);
  EXPECT_FALSE(warned(as_given));
  const Mesh sphere = testing::make_ellipsoid(1);  // 80 triangles, more quads than triangles at the default
  const ParamJob round = parameterize_mesh(sphere, PipelineOptions{});
  EXPECT_FALSE(warned(round));
  EXPECT_EQ(round.options.param.density.default_edge_factor, DensityOptions{}.default_edge_factor);
}

// When the memory budget refuses the finer default density, the coarser attempt is kept and a warning says why.
TEST(ValidityRetries, AFinerDefaultDensityTheMemoryCannotHoldKeepsTheCoarserAttempt) {
  const Mesh tube = testing::make_torus(60, 6, 1.0, 0.02);
  PipelineOptions options;
  const double quads = requested_quads(tube, options.param);  // attempt 0; half the edge asks for 4 times as many
  options.max_memory_bytes =
      static_cast<std::int64_t>(kBytesPerInputFace * tube.num_faces() + kBytesPerQuad * 2 * quads);
  const ParamJob job = parameterize_mesh(tube, options);
  EXPECT_EQ(job.options.param.density.default_edge_factor, DensityOptions{}.default_edge_factor);
  EXPECT_TRUE(std::any_of(job.warnings.begin(), job.warnings.end(), [](const std::string& w) {
    return w.find("a finer one was refused") != std::string::npos && w.find("GB are available") != std::string::npos;
  }));
}

}  // namespace
}  // namespace quadcover
