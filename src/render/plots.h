#pragma once
// Generic plots as SVG text or PNG images: line plots (e.g. E_D and the branch point count over the iterations of
// Algorithm 6.1, Fig. 6.1; E_D, E_H and E_D + E_H over the branch point count, Fig. 6.5) and histograms (per-triangle
// ARAP energy, edge lengths, angles: Fig. 6.2, 7.1). They take plain vectors, so any stage's data feeds in.
#include <optional>
#include <string>
#include <vector>

#include "render/image.h"

namespace quadcover {

/// One curve: points (x[i], y[i]); x and y have the same length.
struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  bool right_axis = false;  ///< plotted against the secondary (right) y axis, e.g. a count next to an energy
  bool markers = false;     ///< draw a dot at every point
};

struct LinePlot {
  std::string title, x_label, y_label;
  std::string y2_label;  ///< label of the right axis (used when a series has right_axis)
  std::vector<PlotSeries> series;
};

struct Histogram {
  std::string title, x_label;
  std::string y_label = "count";
  std::vector<double> values;
  std::vector<double> weights;  ///< optional, same length as values (e.g. triangle areas); empty = count
  int bins = 30;
  std::optional<double> lo, hi;  ///< range; default: min / max of the values
};

/// Bin totals of a histogram over [lo, hi] in `bins` equal bins (values outside are clamped into the end bins,
/// non-finite ones dropped). Exposed for tests and for reports.
/// \pre h.weights is empty or as long as h.values; h.bins >= 1.
std::vector<double> histogram_counts(const Histogram& h, double* lo_out = nullptr, double* hi_out = nullptr);

/// s with &, <, > and " escaped, for HTML and SVG text. \pre none
std::string escape_markup(const std::string& s);

/// "Nice" tick positions (1, 2, 5 × 10^k steps) covering [lo, hi] with about `target` ticks. \pre target >= 1
std::vector<double> nice_ticks(double lo, double hi, int target = 5);

std::string line_plot_svg(const LinePlot& plot, int width = 640, int height = 400);  ///< \pre width, height >= 1
Image line_plot_image(const LinePlot& plot, int width = 640, int height = 400);  ///< \pre width, height >= 1
/// \pre width, height >= 1; as histogram_counts.
std::string histogram_svg(const Histogram& histogram, int width = 640, int height = 400);
/// \pre width, height >= 1; as histogram_counts.
Image histogram_image(const Histogram& histogram, int width = 640, int height = 400);

/// Writes a line plot by extension: ".svg" as SVG text, anything else as PNG (atomically).
/// \pre width, height >= 1. \throw InputError if path cannot be written.
void write_line_plot(const std::string& path, const LinePlot& plot, int width = 640, int height = 400);

}  // namespace quadcover
