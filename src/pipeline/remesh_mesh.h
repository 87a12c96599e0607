#pragma once
// The remesh job: the parameterization job (pipeline/parameterize_mesh.h) → quad extraction along the integer
// iso-lines (thesis ch. 7, QEx-style) → tangential smoothing on the input surface. One call for the CLI's `remesh`,
// the Python module and the benches.
#include "pipeline/boundary_loop_check.h"
#include "pipeline/parameterize_mesh.h"
#include "pipeline/surface_check.h"
#include "quad/extract_quads.h"
#include "quad/smooth_quads.h"

namespace quadcover {

struct RemeshJob {
  ParamJob param;
  ExtractionResult extraction;  ///< the quad mesh (smoothed) and what extraction did
  QuadSmoothingReport smoothing;
  SurfaceCheck surface;  ///< the quad mesh against the input; its problems are in param.warnings
  std::vector<BoundaryLoopCheck> boundary_loops;  ///< per boundary loop: followed by quads, or why not
};

/// The ParamJob of a remesh job (for the validity retries). \pre none
inline ParamJob& param_job(RemeshJob& job) { return job.param; }

/// Runs the remesh job on `mesh`, again at nearby densities while the map is not valid or the quad mesh's topology
/// differs from the input's (options.validity_retries, pipeline/validity_retries.h).
/// \pre mesh is a valid triangle mesh (build_mesh).
/// \throw InputError for invalid options or a density whose map holds fewer than 4 quads (the message says how to
/// ask for more); NumericalError if a factorization fails or the extraction yields no face.
RemeshJob remesh_mesh(const Mesh& mesh, const PipelineOptions& options, ProgressSink& progress = null_progress());

}  // namespace quadcover
