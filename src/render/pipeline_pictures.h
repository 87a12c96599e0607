#pragma once
// One-call pictures and reports for the pipeline commands (`param --png`, `remesh --png`, `--report-html`):
// a parameterization as a checkerboard with seams and branch points, a quad mesh as wireframe, and the HTML page.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mesh/mesh.h"
#include "metrics/param_quality.h"
#include "param/parameterization.h"
#include "quad/quad_mesh.h"
#include "render/render_mesh.h"

namespace quadcover {

/// PNG of the map: checkerboard of the unit grid (one square = one quad), cut edges where φ jumps, branch points
/// coloured by index. Several views are tiled side by side (default: front). Written atomically.
/// \pre param belongs to mesh. \throw InputError if path cannot be written.
void write_parameterization_png(const std::string& path, const Mesh& mesh, const Parameterization& param,
                                const std::vector<ViewCamera>& views = {ViewCamera{}}, RenderOptions options = {});

/// PNG of a quad (polygon) mesh as wireframe over flat shading; several views are tiled. Written atomically.
/// \pre face indices are rows of quads.V. \throw InputError if path cannot be written.
void write_quad_mesh_png(const std::string& path, const QuadMesh& quads,
                         const std::vector<ViewCamera>& views = {ViewCamera{}}, RenderOptions options = {});

/// The HTML report of a run: `report` as the metrics table (and its optimize log as the Fig. 6.1 plot), the textured
/// mesh (when param is given), the quad mesh with its edge-length and angle histograms (when quads is given), and
/// the per-triangle ARAP histogram (when quality is given). Written atomically.
/// \pre param, quads, quality belong to mesh when given. \throw InputError if path cannot be written.
void write_pipeline_report(const std::string& path, const std::string& title, const Mesh& mesh,
                           const Parameterization* param, const QuadMesh* quads, const nlohmann::json& report,
                           const ParamQuality* quality = nullptr);

}  // namespace quadcover
