#pragma once
// An 8-bit RGB image, PNG encoding (libpng) and an atomic PNG writer.
#include <cstdint>
#include <string>
#include <vector>

namespace quadcover {

/// A colour with components in [0, 1].
struct Rgb {
  double r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

/// width × height pixels, row-major from the top-left, 3 bytes (R, G, B) per pixel.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;

  Image() = default;
  Image(int w, int h, Rgb fill = {1, 1, 1});  ///< \pre w, h >= 0
  void set(int x, int y, Rgb c);  ///< \pre 0 <= x < width, 0 <= y < height
  Rgb at(int x, int y) const;  ///< \pre 0 <= x < width, 0 <= y < height
  /// \pre 0 <= x < width, 0 <= y < height
  const std::uint8_t* pixel(int x, int y) const {
    return pixels.data() + 3 * (static_cast<std::size_t>(y) * width + x);
  }
};

/// The image as PNG file bytes (8-bit RGB, no interlace). \throw std::runtime_error if libpng fails.
std::string encode_png(const Image& image);
/// Decodes PNG bytes (any colour type; converted to 8-bit RGB). \throw InputError naming `name` if invalid.
Image decode_png(const std::string& bytes, const std::string& name = "<png>");
/// Writes a PNG atomically (temporary file + rename). \throw InputError naming the path on failure.
void write_png(const std::string& path, const Image& image);
/// Reads a PNG file. \throw InputError naming the path.
Image read_png(const std::string& path);

/// Images side by side (top-aligned) with `gap` pixels of `fill` between them. \pre gap >= 0
Image tile_horizontally(const std::vector<Image>& images, int gap = 8, Rgb fill = {1, 1, 1});

}  // namespace quadcover
