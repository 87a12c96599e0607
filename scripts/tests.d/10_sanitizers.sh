#!/usr/bin/env bash
# The whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer (leak checking on; UBSan without its null,
# alignment and object-size checks, see CMakeLists.txt): configures
# build-asan/ (-O1 -g1: less compile time than -O2 and fast enough to run; line tables for the reports,
# -DQUADCOVER_SANITIZE=ON), builds the test executables of STAGES and runs their ctest labels there.
# Any sanitizer report aborts the test that triggered it, which fails the step. Uses ccache when installed.
# SANITIZE_LABELS (a ctest -L regex) narrows the run for local use, e.g. SANITIZE_LABELS='io|mesh'.
# The heaviest tests (HEAVY below: whole-job CLI tests of 44-320 s each under ASan, together about 1000 of the cli label's
# 1060 and of all 1810 test-seconds, and the param tests over 20 s, measured 2026-12-03) run in the Release ctest
# only; the code they reach runs here in the smaller CLI and stage tests.
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=build-asan
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
cmake -S . -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DQUADCOVER_SANITIZE=ON -DQUADCOVER_BUILD_BENCH=OFF "${launcher[@]}" >/dev/null
# Every stage's tests (the CLI tests run the sanitized CLI binary).
STAGES=(io mesh calculus topology field cover param optimize quad metrics render cli)
TARGETS=()
for s in "${STAGES[@]}"; do TARGETS+=("test_$s"); done
TARGETS+=(quadcover)
# -k 0: build every target that compiles, so one broken file still leaves the other tests running (the step
# fails either way).
build_status=0
cmake --build "$BUILD" -j"${JOBS:-$(nproc)}" --target "${TARGETS[@]}" -- -k 0 || build_status=$?
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
LABELS=${SANITIZE_LABELS:-$(IFS='|'; echo "${STAGES[*]}")}
test_status=0
HEAVY='^(AdversarialCli\.(ManyComponents|HundredsOfBoundaryLoops)|PlyOutputCli\.ParamPlyHasTheObjTexcoordsPerCorner|OptimizeCli\.(KeepBetterNeverReturnsAWorseMapThanEitherField|RelocationLowersCurlEnergyAndNeverAddsBranchPoints)|JobWarningsCli\.EveryReportWarningIsOnStderrAndTheSurfaceCheckMatchesTheFile|OneTruthCli\.RemeshSurfaceCheckMatchesInfoAndMetricsOfTheOutput|FeatureAngleCli\.OffKeepsTheBoundariesAligned'
# ... and the param tests over 20 s under ASan (the same stages run here on the smaller meshes of their suites).
HEAVY+='|Untangle\.ReleasingCurveCornersOpensStuckCurveTriangles|Meshes/WithCurves\..*/(camelhead_boundary|bunny_20k_holes)'
HEAVY+='|Meshes/OnTestMeshes\.(SeamlessIntegerGridMap|SymmetricPeriodCount|DensityFollowsTargetQuadCount)/(spot_gen|camelhead_boundary_curv)'
# ... and the whole-job tests over 15 s under ASan whose stages run here in smaller tests of the same suites
# (measured 2026-12-04: together about 260 of the 1000 test-seconds left).
HEAVY+='|MeshesWithBoundary/OneEnergy\..*/"camelhead_boundary"|Meshes/(SmoothShipped|ShippedMeshes)\..*/"camelhead_boundary(\.obj)?"'
HEAVY+='|FeatureAngleCli\.AngleReachesTheFieldStageAndTheReport|PlyOutputCli\.RemeshQualityPlyMatchesTheObjOutput'
HEAVY+='|ParamCli\.WritesSeamlessObjAndReport|Commands/BatchParallel\..*/"remesh"|RemeshSmoothingCli\.MovesVerticesKeepsFacesAndIsReported'
# ... and those over 10 s under ASan (measured 2026-12-07, about 110 of the 850 test-seconds left) whose code runs
# here in smaller tests: the field's fill and splits (field label), the other curve-rounding, curl-reduction,
# relaxation and density tests, and the given-features test beside the saved-features one.
# (No parentheses in these: CMake's regular expressions allow 10 groups, the lines above use them.)
HEAVY+='|FillCli\.PropagateChangesTheFieldAndTheDefaultIsSmooth|FillCli\.SplitConesChoosesWhichSingularitiesAreSplit'
HEAVY+='|FeatureAngleCli\.SavedFeaturesGiveBackTheSameQuads|CurlReduction\.NoTriangleGetsABranchPointAtEachCorner'
HEAVY+='|CurveRounding\.FreesExactlyTheLinesThroughTheGivenVertices'
HEAVY+='|CurveRounding\.CountsTheLinesLengthsInTheirComponentsGridUnits'
HEAVY+='|Meshes/OnTestMeshes\.RequestedCountScalesTheFreeMap/camelhead_boundary_curv'
HEAVY+='|Meshes/RelaxedMeshes\.LessDistortedAndStillSeamless/camelhead_boundary'
HEAVY+=')( |$)'
ctest --test-dir "$BUILD" --output-on-failure -j"${JOBS:-$(nproc)}" --timeout 900 -L "$LABELS" -E "$HEAVY" ||
  test_status=$?
if ((build_status)); then echo "10_sanitizers: the sanitizer build failed (see above)" >&2; fi
exit $((build_status || test_status))
