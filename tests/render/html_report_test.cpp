// The HTML report is one self-contained page: metrics table, inline SVG figures, mesh data and three.js inlined,
// nothing fetched from elsewhere, and nothing that would end an inline script early.
#include "render/html_report.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <regex>

#include "support/test_meshes.h"
#include "support/text.h"

namespace quadcover {
namespace html_assets {
std::string_view three_js();
std::string_view viewer_js();
}  // namespace html_assets
namespace {

using testing::between;

std::string read_source_file(const std::string& relative) {
  std::ifstream in(std::string(QUADCOVER_TEST_DATA_DIR) + "/../../" + relative, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(HtmlAssets, ThreeJsAndViewerAreEmbeddedAndSafeToInline) {
  // Embedded byte for byte (html/embed.cmake): a truncated or re-encoded asset would break the page.
  const std::string three = read_source_file("html/vendor/three.module.min.js");
  ASSERT_FALSE(three.empty());
  EXPECT_EQ(html_assets::three_js(), three);
  EXPECT_EQ(html_assets::viewer_js(), read_source_file("html/viewer.js"));
  EXPECT_NE(html_assets::three_js().find("WebGLRenderer"), std::string_view::npos);
  EXPECT_NE(html_assets::viewer_js().find("qc-data"), std::string_view::npos);
  for (std::string_view asset : {html_assets::three_js(), html_assets::viewer_js()}) {
    std::string lower(asset);
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    EXPECT_EQ(lower.find("</script"), std::string::npos);
    EXPECT_EQ(lower.find("<!--"), std::string::npos);
  }
}

TEST(HtmlReport, PageHoldsMetricsFiguresAndMeshData) {
  const Mesh grid = testing::make_grid(3);
  Eigen::MatrixX3cd uv(grid.num_faces(), 3);
  for (int f = 0; f < grid.num_faces(); ++f)
    for (int c = 0; c < 3; ++c) uv(f, c) = {3 * grid.V()(grid.F()(f, c), 0), 3 * grid.V()(grid.F()(f, c), 1)};
  std::vector<std::vector<int>> tris;
  for (int f = 0; f < grid.num_faces(); ++f) tris.push_back({grid.F()(f, 0), grid.F()(f, 1), grid.F()(f, 2)});

  HtmlReport r;
  r.title = "grid <test>";
  r.metrics = {{"E_D", 0.25},
               {"seamless", true},
               {"branch_points", {{"+1", 8}}},
               {"optimize",
                {{"mode", "relocate"},
                 {"log",
                  {{{"phase", "start"}, {"evaluation", 0}, {"E_D", 2.0}, {"branch_points", 4}},
                   {{"phase", "reduce"}, {"evaluation", 7}, {"E_D", 1.0}, {"branch_points", 6}}}}}}};
  r.figures = figures_from_report(r.metrics);
  ASSERT_EQ(r.figures.size(), 1u);  // Fig. 6.1 from the optimize log (what param / remesh reports hold)
  r.meshes.push_back({"textured", grid.V(), tris, uv, false});
  r.meshes.push_back({"quads", grid.V(), tris, {}, true});
  const std::string page = html_report(r);

  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(page.find("<title>grid &lt;test&gt;</title>"), std::string::npos);
  const std::string table = between(page, "<table id=\"qc-metrics\">", "</table>");
  EXPECT_NE(table.find("<td>branch_points.+1</td><td class=\"v\">8</td>"), std::string::npos);
  EXPECT_NE(table.find("<td>E_D</td><td class=\"v\">0.25</td>"), std::string::npos);
  EXPECT_EQ(table.find("optimize.log"), std::string::npos);  // drawn, not tabulated
  EXPECT_NE(table.find("<td>optimize.mode</td><td class=\"v\">relocate</td>"), std::string::npos);
  std::size_t svgs = 0;
  for (std::size_t p = 0; (p = page.find("<svg", p)) != std::string::npos; ++p) ++svgs;
  EXPECT_EQ(svgs, 1u);
  EXPECT_EQ(std::count(page.begin(), page.end(), '\0'), 0);

  const auto data =
      nlohmann::json::parse(between(page, "<script type=\"application/json\" id=\"qc-data\">", "</script>"));
  ASSERT_EQ(data["meshes"].size(), 2u);
  EXPECT_EQ(data["meshes"][0]["triangles"].size(), 3u * grid.num_faces());
  EXPECT_EQ(data["meshes"][0]["uv"].size(), 6u * grid.num_faces());
  EXPECT_EQ(data["meshes"][0]["positions"].size(), 3u * grid.num_vertices());
  EXPECT_FALSE(data["meshes"][0].contains("edges"));
  EXPECT_EQ(data["meshes"][1]["edges"].size(), 2u * grid.num_edges());  // every edge once
  EXPECT_EQ(std::count(page.begin(), page.end(), '\n') > 10, true);
  // Self-contained: no external scripts, styles or images.
  EXPECT_FALSE(std::regex_search(page, std::regex("<script[^>]*\\ssrc=")));
  EXPECT_FALSE(std::regex_search(page, std::regex("<link[^>]*href=")));
  EXPECT_FALSE(std::regex_search(page, std::regex("<img[^>]*src=\"https?:")));
  // Exactly the scripts we put there: the data, three.js as text, the viewer module.
  std::size_t scripts = 0;
  for (std::size_t p = 0; (p = page.find("<script", p)) != std::string::npos; ++p) ++scripts;
  EXPECT_EQ(scripts, 3u);
  EXPECT_EQ(between(page, "<script type=\"text/plain\" id=\"qc-three\">", "</script>"), html_assets::three_js());
  // The metrics in the page's data are the report's: every scalar of r.metrics is in the table with its value.
  EXPECT_NE(table.find("<td>seamless</td><td class=\"v\">true</td>"), std::string::npos);
}

TEST(HtmlReport, QuadMeshFiguresMeasureEdgesAndAngles) {
  // A 2 × 1 strip of unit squares: 7 edges of length 1, 8 corners of 90°.
  Eigen::MatrixX3d V(6, 3);
  V << 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0;
  const auto figs = polygon_mesh_figures(V, {{0, 1, 4, 3}, {1, 2, 5, 4}});
  ASSERT_EQ(figs.size(), 2u);
  EXPECT_NE(figs[0].second.find(">1<"), std::string::npos);  // the single bar sits at length / mean = 1
  // One bar each: all lengths equal the mean, all angles are 90°.
  for (const auto& [caption, svg] : figs) {
    std::size_t bars = 0;
    for (std::size_t p = 0; (p = svg.find("fill=\"#1f77b4\"", p)) != std::string::npos; ++p) ++bars;
    EXPECT_EQ(bars, 1u) << caption;
  }
}

}  // namespace
}  // namespace quadcover
