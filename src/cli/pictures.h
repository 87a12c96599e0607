#pragma once
// Pictures and pages written by the pipeline commands (param, remesh) next to their main output: --png (a rendered
// view), --report-html (the self-contained HTML report with the metrics, the Fig. 6.1 plot and 3D views) and
// --plot (thesis Fig. 6.1 as PNG or SVG). Also the --view / --size parsers shared with `render`.
#include <CLI/CLI.hpp>
#include <string>
#include <utility>
#include <vector>

#include "render/canvas.h"
#include "render/render_mesh.h"

namespace quadcover::cli {

/// "WxH" with 16 <= W, H <= 8192. \throw InputError naming --size otherwise.
std::pair<int, int> parse_size(const std::string& s);

/// "front", "side", "top", "back", "bottom", "iso", "all" (front, side and top side by side) or "AZ,EL" in degrees.
/// \throw InputError naming --view otherwise.
std::vector<ViewCamera> parse_views(const std::string& s);

struct PictureCliOptions {
  std::string png;          ///< rendered picture (empty: none)
  std::string report_html;  ///< HTML report (empty: none)
  std::string plot;         ///< Fig. 6.1 plot, .svg or .png (empty: none)
  std::string view = "front";
  std::string size = "800x800";
};

/// Adds --png (described by `png_description`), --view, --size, --report-html and --plot to `cmd`.
/// \pre options outlives cmd.
void add_picture_options(CLI::App& cmd, PictureCliOptions& options, const std::string& png_description);

/// Render options (size) and cameras from the parsed options; validates both (call before the long stages so a
/// bad --view fails at once). \throw InputError naming --size for a malformed size.
RenderOptions picture_render_options(const PictureCliOptions& options);
/// \throw InputError naming --view for a malformed view.
std::vector<ViewCamera> picture_views(const PictureCliOptions& options);

}  // namespace quadcover::cli
