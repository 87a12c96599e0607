// Plots: bins and ticks are computed right, SVG and PNG show the data (bars, curves, labels).
#include "render/plots.h"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>

#include "render/bitmap_font.h"

namespace quadcover {
namespace {

TEST(Histogram, CountsAndWeightsPerBin) {
  Histogram h;
  h.values = {0.0, 0.05, 0.15, 0.95, 1.0, std::nan(""), 0.5};
  h.bins = 10;
  h.lo = 0.0;
  h.hi = 1.0;
  const auto c = histogram_counts(h);
  ASSERT_EQ(c.size(), 10u);
  EXPECT_EQ(c[0], 2);  // 0 and 0.05
  EXPECT_EQ(c[1], 1);
  EXPECT_EQ(c[5], 1);
  EXPECT_EQ(c[9], 2);  // 0.95 and the upper end 1.0
  double total = 0;
  for (double v : c) total += v;
  EXPECT_EQ(total, 6);  // NaN dropped
  h.weights = {1, 1, 2, 1, 1, 1, 0.5};
  EXPECT_EQ(histogram_counts(h)[1], 2);
  EXPECT_EQ(histogram_counts(h)[5], 0.5);
}

TEST(Ticks, NiceStepsCoverTheRange) {
  const auto t = nice_ticks(0, 1, 5);
  ASSERT_EQ(t.size(), 6u);
  EXPECT_NEAR(t[1] - t[0], 0.2, 1e-12);
  const auto u = nice_ticks(13, 87, 5);
  EXPECT_NEAR(u[1] - u[0], 10, 1e-9);  // range 74 / 5 ticks = 14.8 -> step 10
  EXPECT_GE(u.front(), 13);
  EXPECT_LE(u.back(), 87);
  EXPECT_TRUE(nice_ticks(1, 1).empty());
}

TEST(LinePlot, SvgHasOneCurvePerSeriesWithAllPointsAndLabels) {
  LinePlot p;
  p.title = "Algorithm 6.1";
  p.x_label = "iteration";
  p.y_label = "E_D";
  p.y2_label = "branch points";
  PlotSeries ed{"E_D", {0, 1, 2, 3}, {10, 7, 5, 4.5}};
  PlotSeries bp{"branch points", {0, 1, 2, 3}, {40, 44, 48, 50}, true};
  p.series = {ed, bp};
  const std::string svg = line_plot_svg(p);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  const std::regex polyline("<polyline[^>]*points=\"([^\"]*)\"");
  int curves = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), polyline); it != std::sregex_iterator(); ++it) {
    const std::string pts = (*it)[1];
    EXPECT_EQ(std::count(pts.begin(), pts.end(), ','), 4);
    ++curves;
  }
  EXPECT_EQ(curves, 2);
  EXPECT_NE(svg.find(">Algorithm 6.1<"), std::string::npos);
  EXPECT_NE(svg.find(">branch points<"), std::string::npos);  // right axis label
  // E_D decreases: the first point is higher on the page (smaller y) than the last one.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, polyline));
  std::istringstream pts(m[1]);
  double x0, y0, x3, y3;
  char comma;
  pts >> x0 >> comma >> y0;
  for (int i = 0; i < 3; ++i) pts >> x3 >> comma >> y3;
  EXPECT_LT(y0, y3);
  EXPECT_LT(x0, x3);
}

TEST(Histogram, SvgBarsMatchNonEmptyBinsAndPngShowsThem) {
  Histogram h;
  h.title = "ARAP";
  for (int i = 0; i < 100; ++i) h.values.push_back((i % 10) < 7 ? 0.1 : 0.9);  // two clusters
  h.bins = 20;
  h.lo = 0;
  h.hi = 1;
  const std::string svg = histogram_svg(h);
  const std::regex bar("<rect x=\"[^\"]*\" y=\"[^\"]*\" width=\"[^\"]*\" height=\"([^\"]*)\" fill=\"#1f77b4\"");
  std::vector<double> heights;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), bar); it != std::sregex_iterator(); ++it)
    heights.push_back(std::stod((*it)[1]));
  ASSERT_EQ(heights.size(), 2u);
  EXPECT_NEAR(heights[0] / heights[1], 70.0 / 30.0, 1e-4);  // SVG numbers have 6 digits

  const Image im = histogram_image(h, 400, 300);
  int blue = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const Rgb c = im.at(x, y);
      blue += c.b > 0.6 && c.r < 0.25;
    }
  EXPECT_GT(blue, 500);
}

TEST(Font, PlotCharactersHaveDistinctGlyphsInsideTheirCell) {
  // Every character a plot label uses must be legible: its own glyph (no two alike, none blank), inside the 5×7
  // cell (bits 0-4 only).
  const std::string chars = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ.-+%()_/:=";
  for (std::size_t i = 0; i < chars.size(); ++i) {
    const auto g = glyph_5x7(chars[i]);
    int bits = 0;
    for (auto row : g) {
      EXPECT_EQ(row & ~0x1F, 0) << chars[i];
      bits += __builtin_popcount(row);
    }
    EXPECT_GT(bits, 0) << chars[i];
    for (std::size_t j = 0; j < i; ++j) EXPECT_NE(g, glyph_5x7(chars[j])) << chars[i] << " and " << chars[j];
  }
  // Lower case is drawn as upper case; space and unknown characters are blank.
  for (char c = 'a'; c <= 'z'; ++c) EXPECT_EQ(glyph_5x7(c), glyph_5x7(static_cast<char>(c - 'a' + 'A'))) << c;
  EXPECT_EQ(glyph_5x7(' '), (std::array<std::uint8_t, 7>{}));
  EXPECT_EQ(glyph_5x7('\x7f'), (std::array<std::uint8_t, 7>{}));
  // A few shapes by their pixels: '-' is one horizontal stroke in the middle row, '1' and 'I' have a vertical
  // stroke through the middle column, '0' is closed left and right.
  EXPECT_EQ(glyph_5x7('-'), (std::array<std::uint8_t, 7>{0, 0, 0, 0x0E, 0, 0, 0}));
  for (char c : {'1', 'I'})
    for (int r = 1; r < 6; ++r) EXPECT_TRUE(glyph_5x7(c)[r] & 0x04) << c << " row " << r;
  for (int r = 1; r < 6; ++r) EXPECT_EQ(glyph_5x7('0')[r] & 0x11, 0x11) << r;
}

}  // namespace
}  // namespace quadcover
