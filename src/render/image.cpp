#include "render/image.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include "common/errors.h"
#include "io/atomic_file.h"
#include "io/read_mesh.h"

namespace quadcover {

namespace {
std::uint8_t to_byte(double c) { return static_cast<std::uint8_t>(std::lround(std::clamp(c, 0.0, 1.0) * 255.0)); }
}  // namespace

Image::Image(int w, int h, Rgb fill) : width(w), height(h), pixels(static_cast<std::size_t>(w) * h * 3) {
  for (std::size_t i = 0; i < pixels.size(); i += 3) {
    pixels[i] = to_byte(fill.r);
    pixels[i + 1] = to_byte(fill.g);
    pixels[i + 2] = to_byte(fill.b);
  }
}

void Image::set(int x, int y, Rgb c) {
  std::uint8_t* p = pixels.data() + 3 * (static_cast<std::size_t>(y) * width + x);
  p[0] = to_byte(c.r);
  p[1] = to_byte(c.g);
  p[2] = to_byte(c.b);
}

Rgb Image::at(int x, int y) const {
  const std::uint8_t* p = pixel(x, y);
  return {p[0] / 255.0, p[1] / 255.0, p[2] / 255.0};
}

namespace {
struct PngWriteGuard {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngWriteGuard() { png_destroy_write_struct(&png, &info); }
};
struct PngReadGuard {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~PngReadGuard() { png_destroy_read_struct(&png, &info, nullptr); }
};
struct ReadCursor {
  const std::string* bytes;
  std::size_t pos;
};
}  // namespace

std::string encode_png(const Image& image) {
  std::string out;
  PngWriteGuard g;
  g.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!g.png) throw std::runtime_error("libpng: cannot create write struct");
  g.info = png_create_info_struct(g.png);
  if (!g.info) throw std::runtime_error("libpng: cannot create info struct");
  if (setjmp(png_jmpbuf(g.png))) throw std::runtime_error("libpng: encoding failed");
  png_set_write_fn(
      g.png, &out,
      [](png_structp p, png_bytep data, png_size_t n) {
        static_cast<std::string*>(png_get_io_ptr(p))->append(reinterpret_cast<const char*>(data), n);
      },
      nullptr);
  png_set_IHDR(g.png, g.info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(g.png, g.info);
  for (int y = 0; y < image.height; ++y) png_write_row(g.png, const_cast<png_bytep>(image.pixel(0, y)));
  png_write_end(g.png, nullptr);
  return out;
}

Image decode_png(const std::string& bytes, const std::string& name) {
  if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) != 0)
    throw InputError(name, 0, "not a PNG file");
  PngReadGuard g;
  g.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!g.png) throw std::runtime_error("libpng: cannot create read struct");
  g.info = png_create_info_struct(g.png);
  if (!g.info) throw std::runtime_error("libpng: cannot create info struct");
  if (setjmp(png_jmpbuf(g.png))) throw InputError(name, 0, "corrupt PNG data");
  ReadCursor cursor{&bytes, 0};
  png_set_read_fn(g.png, &cursor, [](png_structp p, png_bytep data, png_size_t n) {
    auto* c = static_cast<ReadCursor*>(png_get_io_ptr(p));
    if (c->pos + n > c->bytes->size()) png_error(p, "truncated");
    std::memcpy(data, c->bytes->data() + c->pos, n);
    c->pos += n;
  });
  png_read_info(g.png, g.info);
  png_set_strip_16(g.png);
  png_set_strip_alpha(g.png);
  png_set_palette_to_rgb(g.png);
  png_set_expand_gray_1_2_4_to_8(g.png);
  png_set_gray_to_rgb(g.png);
  png_read_update_info(g.png, g.info);
  Image image(static_cast<int>(png_get_image_width(g.png, g.info)),
              static_cast<int>(png_get_image_height(g.png, g.info)));
  if (png_get_rowbytes(g.png, g.info) != static_cast<png_size_t>(image.width) * 3)
    throw InputError(name, 0, "unsupported PNG layout");
  for (int y = 0; y < image.height; ++y)
    png_read_row(g.png, image.pixels.data() + static_cast<std::size_t>(y) * image.width * 3, nullptr);
  return image;
}

void write_png(const std::string& path, const Image& image) {
  const std::string bytes = encode_png(image);
  write_file_atomically(
      path, [&](std::ostream& out) { out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
}

Image read_png(const std::string& path) { return decode_png(read_file_bytes(path), path); }

Image tile_horizontally(const std::vector<Image>& images, int gap, Rgb fill) {
  int w = 0, h = 0;
  for (const Image& im : images) {
    w += im.width;
    h = std::max(h, im.height);
  }
  if (!images.empty()) w += gap * (static_cast<int>(images.size()) - 1);
  Image out(w, h, fill);
  int x0 = 0;
  for (const Image& im : images) {
    for (int y = 0; y < im.height; ++y)
      std::memcpy(out.pixels.data() + 3 * (static_cast<std::size_t>(y) * w + x0), im.pixel(0, y),
                  static_cast<std::size_t>(im.width) * 3);
    x0 += im.width + gap;
  }
  return out;
}

}  // namespace quadcover
