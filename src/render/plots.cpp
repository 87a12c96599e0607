#include "render/plots.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "io/atomic_file.h"
#include "render/bitmap_font.h"
#include "render/canvas.h"

namespace quadcover {

namespace {

const char* const kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};

// ---- two back ends behind one drawing interface -----------------------------------------------------------------

enum class Anchor { Start, Middle, End };

class Painter {
 public:
  virtual ~Painter() = default;
  virtual void line(double x0, double y0, double x1, double y1, const std::string& color, double width) = 0;
  virtual void polyline(const std::vector<std::pair<double, double>>& pts, const std::string& color, double width) = 0;
  virtual void rect(double x, double y, double w, double h, const std::string& fill) = 0;
  virtual void circle(double x, double y, double r, const std::string& fill) = 0;
  /// Text with its baseline at y (vertical: rotated by -90°, reading upwards, baseline at x).
  virtual void text(double x, double y, const std::string& s, double size, Anchor anchor, bool vertical) = 0;
};

class SvgPainter final : public Painter {
 public:
  SvgPainter(int w, int h) {
    s_ << std::setprecision(6) << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w << "\" height=\"" << h
       << "\" viewBox=\"0 0 " << w << ' ' << h << "\" font-family=\"sans-serif\">\n"
       << "<rect width=\"" << w << "\" height=\"" << h << "\" fill=\"#ffffff\"/>\n";
  }
  void line(double x0, double y0, double x1, double y1, const std::string& c, double w) override {
    s_ << "<line x1=\"" << x0 << "\" y1=\"" << y0 << "\" x2=\"" << x1 << "\" y2=\"" << y1 << "\" stroke=\"" << c
       << "\" stroke-width=\"" << w << "\"/>\n";
  }
  void polyline(const std::vector<std::pair<double, double>>& pts, const std::string& c, double w) override {
    s_ << "<polyline fill=\"none\" stroke=\"" << c << "\" stroke-width=\"" << w << "\" points=\"";
    for (const auto& [x, y] : pts) s_ << x << ',' << y << ' ';
    s_ << "\"/>\n";
  }
  void rect(double x, double y, double w, double h, const std::string& fill) override {
    s_ << "<rect x=\"" << x << "\" y=\"" << y << "\" width=\"" << w << "\" height=\"" << h << "\" fill=\"" << fill
       << "\"/>\n";
  }
  void circle(double x, double y, double r, const std::string& fill) override {
    s_ << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"" << r << "\" fill=\"" << fill << "\"/>\n";
  }
  void text(double x, double y, const std::string& t, double size, Anchor a, bool vertical) override {
    const char* anchor = a == Anchor::Start ? "start" : a == Anchor::Middle ? "middle" : "end";
    s_ << "<text x=\"" << x << "\" y=\"" << y << "\" font-size=\"" << size << "\" text-anchor=\"" << anchor << '"';
    if (vertical) s_ << " transform=\"rotate(-90 " << x << ' ' << y << ")\"";
    s_ << '>' << escape_markup(t) << "</text>\n";
  }
  std::string finish() {
    s_ << "</svg>\n";
    return s_.str();
  }

 private:
  std::ostringstream s_;
};

Rgb parse_hex(const std::string& hex) {
  const auto v = static_cast<unsigned>(std::stoul(hex.substr(1), nullptr, 16));
  return {((v >> 16) & 255) / 255.0, ((v >> 8) & 255) / 255.0, (v & 255) / 255.0};
}

class RasterPainter final : public Painter {
 public:
  RasterPainter(int w, int h) : canvas_(w, h, 3, {1, 1, 1}) {}
  void line(double x0, double y0, double x1, double y1, const std::string& c, double w) override {
    canvas_.draw_line({x0, y0, 0}, {x1, y1, 0}, w, parse_hex(c));
  }
  void polyline(const std::vector<std::pair<double, double>>& pts, const std::string& c, double w) override {
    for (std::size_t i = 0; i + 1 < pts.size(); ++i)
      line(pts[i].first, pts[i].second, pts[i + 1].first, pts[i + 1].second, c, w);
  }
  void rect(double x, double y, double w, double h, const std::string& fill) override {
    const Rgb c = parse_hex(fill);
    const auto flat = [c](const Eigen::Vector3d&) { return c; };
    canvas_.fill_triangle({x, y, 0}, {x + w, y, 0}, {x + w, y + h, 0}, flat, false);
    canvas_.fill_triangle({x, y, 0}, {x + w, y + h, 0}, {x, y + h, 0}, flat, false);
  }
  void circle(double x, double y, double r, const std::string& fill) override {
    canvas_.draw_disk({x, y, 0}, r, parse_hex(fill));
  }
  void text(double x, double y, const std::string& t, double size, Anchor a, bool vertical) override {
    const double px = std::max(1.0, std::round(size / 8.0 * 4) / 4);  // glyph pixel size
    const double advance = 6 * px;
    const double len = advance * static_cast<double>(t.size()) - px;
    double u0 = a == Anchor::Start ? 0 : a == Anchor::Middle ? -len / 2 : -len;
    for (char ch : t) {
      const auto g = glyph_5x7(ch);
      for (int row = 0; row < 7; ++row)
        for (int col = 0; col < 5; ++col) {
          if (!(g[static_cast<std::size_t>(row)] & (0x10 >> col))) continue;
          const double u = u0 + col * px, v = (row - 7) * px;  // v < 0: above the baseline
          if (vertical)
            rect(x + v, y - u - px, px, px, "#222222");
          else
            rect(x + u, y + v, px, px, "#222222");
        }
      u0 += advance;
    }
  }
  Image finish() const { return canvas_.resolve(); }

 private:
  Canvas canvas_;
};

// ---- layout ---------------------------------------------------------------------------------------------------

std::string tick_label(double v, double step) {
  if (std::abs(v) < step * 1e-9) v = 0;
  std::ostringstream s;
  s << std::setprecision(4) << v;
  return s.str();
}

struct Range {
  double lo = 0, hi = 1;
  std::vector<double> ticks;
};

Range nice_range(double lo, double hi) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) lo = 0, hi = 1;
  if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) lo -= 0.5, hi += 0.5;
  Range r;
  r.ticks = nice_ticks(lo, hi);
  const double step = r.ticks.size() > 1 ? r.ticks[1] - r.ticks[0] : (hi - lo);
  r.lo = std::min(lo, std::floor(lo / step + 1e-9) * step);
  r.hi = std::max(hi, std::ceil(hi / step - 1e-9) * step);
  r.ticks = nice_ticks(r.lo, r.hi);
  return r;
}

struct Frame {
  double left, top, w, h;
  Range x, y, y2;
  bool has_y2 = false;
  double sx(double v) const { return left + (v - x.lo) / (x.hi - x.lo) * w; }
  double sy(double v) const { return top + h - (v - y.lo) / (y.hi - y.lo) * h; }
  double sy2(double v) const { return top + h - (v - y2.lo) / (y2.hi - y2.lo) * h; }
};

Frame make_frame(int width, int height, bool has_y2) {
  Frame f{};
  f.left = 72;
  f.top = 36;
  f.w = width - f.left - (has_y2 ? 72 : 24);
  f.h = height - f.top - 52;
  f.has_y2 = has_y2;
  return f;
}

void draw_axes(Painter& p, const Frame& f, const std::string& title, const std::string& xl, const std::string& yl,
               const std::string& y2l) {
  const std::string grid = "#e6e6e6", axis = "#444444";
  for (double t : f.y.ticks) {
    p.line(f.left, f.sy(t), f.left + f.w, f.sy(t), grid, 1);
    p.text(f.left - 6, f.sy(t) + 4, tick_label(t, f.y.ticks.size() > 1 ? f.y.ticks[1] - f.y.ticks[0] : 1), 11,
           Anchor::End, false);
  }
  for (double t : f.x.ticks) {
    p.line(f.sx(t), f.top, f.sx(t), f.top + f.h, grid, 1);
    p.text(f.sx(t), f.top + f.h + 16, tick_label(t, f.x.ticks.size() > 1 ? f.x.ticks[1] - f.x.ticks[0] : 1), 11,
           Anchor::Middle, false);
  }
  if (f.has_y2)
    for (double t : f.y2.ticks)
      p.text(f.left + f.w + 6, f.sy2(t) + 4, tick_label(t, f.y2.ticks.size() > 1 ? f.y2.ticks[1] - f.y2.ticks[0] : 1),
             11, Anchor::Start, false);
  p.line(f.left, f.top + f.h, f.left + f.w, f.top + f.h, axis, 1.2);
  p.line(f.left, f.top, f.left, f.top + f.h, axis, 1.2);
  if (f.has_y2) p.line(f.left + f.w, f.top, f.left + f.w, f.top + f.h, axis, 1.2);
  p.text(f.left + f.w / 2, 22, title, 15, Anchor::Middle, false);
  p.text(f.left + f.w / 2, f.top + f.h + 38, xl, 12, Anchor::Middle, false);
  p.text(18, f.top + f.h / 2, yl, 12, Anchor::Middle, true);
  if (f.has_y2) p.text(f.left + f.w + 62, f.top + f.h / 2, y2l, 12, Anchor::Middle, true);
}

void paint_line_plot(Painter& p, const LinePlot& plot, int width, int height) {
  bool has_y2 = false;
  double xlo = 1e300, xhi = -1e300, ylo = 1e300, yhi = -1e300, y2lo = 1e300, y2hi = -1e300;
  for (const auto& s : plot.series) {
    has_y2 = has_y2 || s.right_axis;
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xlo = std::min(xlo, s.x[i]);
      xhi = std::max(xhi, s.x[i]);
      (s.right_axis ? y2lo : ylo) = std::min(s.right_axis ? y2lo : ylo, s.y[i]);
      (s.right_axis ? y2hi : yhi) = std::max(s.right_axis ? y2hi : yhi, s.y[i]);
    }
  }
  Frame f = make_frame(width, height, has_y2);
  f.x = nice_range(xlo, xhi);
  f.y = nice_range(ylo, yhi);
  if (has_y2) f.y2 = nice_range(y2lo, y2hi);
  draw_axes(p, f, plot.title, plot.x_label, plot.y_label, plot.y2_label);
  std::size_t longest = 0;
  for (const auto& s : plot.series) longest = std::max(longest, s.label.size() + (s.right_axis ? 8 : 0));
  const double legend_x = f.left + f.w - 16 - 30 - 7.5 * static_cast<double>(longest);
  int k = 0;
  for (const auto& s : plot.series) {
    const std::string color = kPalette[k % 6];
    std::vector<std::pair<double, double>> pts;
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
        pts.emplace_back(f.sx(s.x[i]), s.right_axis ? f.sy2(s.y[i]) : f.sy(s.y[i]));
    p.polyline(pts, color, 2);
    if (s.markers || pts.size() == 1)
      for (const auto& [x, y] : pts) p.circle(x, y, 3, color);
    // Legend entry, top right inside the frame.
    const double ly = f.top + 14 + 16 * k;
    p.line(legend_x, ly - 4, legend_x + 22, ly - 4, color, 2.5);
    p.text(legend_x + 28, ly, s.label + (s.right_axis && has_y2 ? " (right)" : ""), 11, Anchor::Start, false);
    ++k;
  }
}

void paint_histogram(Painter& p, const Histogram& hist, int width, int height) {
  double lo = 0, hi = 1;
  const std::vector<double> counts = histogram_counts(hist, &lo, &hi);
  Frame f = make_frame(width, height, false);
  f.x = nice_range(lo, hi);
  f.x.lo = lo;  // bars span exactly the binned range
  f.x.hi = hi;
  f.x.ticks.erase(
      std::remove_if(f.x.ticks.begin(), f.x.ticks.end(), [&](double t) { return t < lo - 1e-12 || t > hi + 1e-12; }),
      f.x.ticks.end());
  const double top = counts.empty() ? 1 : *std::max_element(counts.begin(), counts.end());
  f.y = nice_range(0, top > 0 ? top : 1);
  f.y.lo = 0;
  draw_axes(p, f, hist.title, hist.x_label, hist.y_label, "");
  const double bw = (hi - lo) / std::max<std::size_t>(1, counts.size());
  for (std::size_t b = 0; b < counts.size(); ++b) {
    if (counts[b] <= 0) continue;
    const double x0 = f.sx(lo + b * bw), x1 = f.sx(lo + (b + 1) * bw);
    p.rect(x0 + 0.5, f.sy(counts[b]), std::max(0.5, x1 - x0 - 1), f.sy(0) - f.sy(counts[b]), kPalette[0]);
  }
}

bool ends_with_svg(const std::string& path) {
  return path.size() >= 4 &&
         (path.compare(path.size() - 4, 4, ".svg") == 0 || path.compare(path.size() - 4, 4, ".SVG") == 0);
}

}  // namespace

std::string escape_markup(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return ticks;
  const double raw = (hi - lo) / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / mag;
  const double step = (norm < 1.5 ? 1 : norm < 3 ? 2 : norm < 7 ? 5 : 10) * mag;
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step) ticks.push_back(t);
  return ticks;
}

std::vector<double> histogram_counts(const Histogram& h, double* lo_out, double* hi_out) {
  double lo = 1e300, hi = -1e300;
  for (double v : h.values)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (h.lo) lo = *h.lo;
  if (h.hi) hi = *h.hi;
  if (!(hi >= lo)) lo = 0, hi = 1;
  if (hi == lo) hi = lo + 1;
  const int bins = std::max(1, h.bins);
  std::vector<double> counts(static_cast<std::size_t>(bins), 0.0);
  for (std::size_t i = 0; i < h.values.size(); ++i) {
    const double v = h.values[i];
    if (!std::isfinite(v)) continue;
    const int b = std::clamp(static_cast<int>(std::floor((v - lo) / (hi - lo) * bins)), 0, bins - 1);
    counts[static_cast<std::size_t>(b)] += i < h.weights.size() ? h.weights[i] : 1.0;
  }
  if (lo_out) *lo_out = lo;
  if (hi_out) *hi_out = hi;
  return counts;
}

namespace {

// The figure drawn by `paint` with a Painter of type P (SvgPainter: SVG text, RasterPainter: Image).
template <class P, class Figure>
auto draw(void (*paint)(Painter&, const Figure&, int, int), const Figure& figure, int width, int height) {
  P p(width, height);
  paint(p, figure, width, height);
  return p.finish();
}

// SVG for a ".svg" path, else PNG, written atomically.
template <class Figure>
void write_figure(const std::string& path, void (*paint)(Painter&, const Figure&, int, int), const Figure& figure,
                  int width, int height) {
  if (ends_with_svg(path)) {
    const std::string svg = draw<SvgPainter>(paint, figure, width, height);
    write_file_atomically(path, [&](std::ostream& out) { out << svg; });
  } else {
    write_png(path, draw<RasterPainter>(paint, figure, width, height));
  }
}

}  // namespace

std::string line_plot_svg(const LinePlot& plot, int width, int height) {
  return draw<SvgPainter>(paint_line_plot, plot, width, height);
}

Image line_plot_image(const LinePlot& plot, int width, int height) {
  return draw<RasterPainter>(paint_line_plot, plot, width, height);
}

std::string histogram_svg(const Histogram& histogram, int width, int height) {
  return draw<SvgPainter>(paint_histogram, histogram, width, height);
}

Image histogram_image(const Histogram& histogram, int width, int height) {
  return draw<RasterPainter>(paint_histogram, histogram, width, height);
}

void write_line_plot(const std::string& path, const LinePlot& plot, int width, int height) {
  write_figure(path, paint_line_plot, plot, width, height);
}

}  // namespace quadcover
