#include "cli/pictures.h"

#include <sstream>
#include <stdexcept>

#include "common/errors.h"

namespace quadcover::cli {

std::pair<int, int> parse_size(const std::string& s) {
  int w = 0, h = 0;
  char x = 0;
  std::istringstream in(s);
  if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || w < 16 || h < 16 || w > 8192 || h > 8192 || !in.eof())
    throw InputError("--size", 0, "expected WxH with 16 <= W, H <= 8192, got '" + s + "'");
  return {w, h};
}

std::vector<ViewCamera> parse_views(const std::string& s) {
  if (s == "all") return {named_view("front"), named_view("side"), named_view("top")};
  if (const auto comma = s.find(','); comma != std::string::npos) {
    try {
      std::size_t used_a = 0, used_e = 0;
      const std::string a = s.substr(0, comma), e = s.substr(comma + 1);
      const ViewCamera cam{std::stod(a, &used_a), std::stod(e, &used_e)};
      if (used_a == a.size() && used_e == e.size()) return {cam};
    } catch (const std::exception&) {
    }
    throw InputError("--view", 0, "expected AZIMUTH,ELEVATION in degrees, got '" + s + "'");
  }
  try {
    return {named_view(s)};
  } catch (const std::invalid_argument& e) {
    throw InputError("--view", 0, e.what());
  }
}

void add_picture_options(CLI::App& cmd, PictureCliOptions& options, const std::string& png_description) {
  cmd.add_option("--png", options.png, png_description + " (one input) or a folder for them");
  cmd.add_option("--view", options.view,
                 "Camera of --png: front, side, top, back, bottom, iso, all (front+side+top) or AZ,EL in degrees")
      ->capture_default_str();
  cmd.add_option("--size", options.size, "Pixels per view of --png, WxH")->capture_default_str();
  cmd.add_option("--report-html", options.report_html,
                 "Self-contained HTML report (one input) or a folder for them: metrics, the optimization plot "
                 "(Fig. 6.1), histograms and interactive 3D views; opens offline");
  cmd.add_option("--plot", options.plot,
                 "Thesis Fig. 6.1: E_D and branch points over the E_D evaluations of --optimize, as .svg or .png "
                 "(one input) or a folder for PNGs");
}

RenderOptions picture_render_options(const PictureCliOptions& options) {
  RenderOptions ro;
  std::tie(ro.width, ro.height) = parse_size(options.size);
  return ro;
}

std::vector<ViewCamera> picture_views(const PictureCliOptions& options) { return parse_views(options.view); }

}  // namespace quadcover::cli
