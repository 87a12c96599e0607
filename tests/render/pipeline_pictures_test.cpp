// Pictures of a real pipeline result: the torus parameterization and its quads render, and the report page carries
// both meshes and the ARAP histogram.
#include "render/pipeline_pictures.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "field/compute_frame_field.h"
#include "io/read_mesh.h"
#include "param/parameterize.h"
#include "quad/extract_quads.h"
#include "support/test_meshes.h"

namespace quadcover {
namespace {

namespace fs = std::filesystem;

TEST(PipelinePictures, ParameterizationPngShowsCheckerSeamsAndCones) {
  const Mesh mesh = testing::load_test_mesh("bunny_3k");
  const Parameterization p = parameterize(mesh, compute_frame_field(mesh));
  ASSERT_FALSE(p.branch_points.empty());
  const fs::path dir = fs::temp_directory_path() / ("qc_pipeline_png_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  RenderOptions o;
  o.width = o.height = 300;
  // Per picture: surface pixels (not background), blue checker pixels, seam-coloured pixels.
  struct Counts {
    int surface = 0, dark = 0, seam = 0;
  };
  auto render = [&](const RenderOptions& options) {
    write_parameterization_png((dir / "p.png").string(), mesh, p, {named_view("front"), named_view("side")}, options);
    const Image im = read_png((dir / "p.png").string());
    EXPECT_EQ(im.width, 2 * 300 + 8);
    EXPECT_EQ(im.height, 300);
    Counts n;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) {
        const Rgb c = im.at(x, y);
        n.surface += c.r < 0.98 || c.g < 0.98 || c.b < 0.98;
        n.dark += c.b > c.r + 0.15;  // blue checker squares
        n.seam += std::abs(c.r - o.seam_color.r) < 0.05 && std::abs(c.g - o.seam_color.g) < 0.05 &&
                  std::abs(c.b - o.seam_color.b) < 0.05;
      }
    return n;
  };
  const Counts with = render(o);
  // A checkerboard of one-quad squares covers about half of the surface with dark squares.
  EXPECT_GT(with.dark, 0.3 * with.surface);
  EXPECT_LT(with.dark, 0.7 * with.surface);
  EXPECT_GT(with.seam, 0);
  // The dark pixels come from the texture (and the blue branch point dots) and the seam-coloured ones from the
  // seams: without them they are gone.
  RenderOptions plain = o;
  plain.texture = SurfaceTexture::None;
  plain.show_seams = false;
  plain.show_branch_points = false;
  const Counts without = render(plain);
  EXPECT_EQ(without.seam, 0);
  EXPECT_LT(without.dark, 0.001 * without.surface);
  // The same silhouette, up to the dots and seam lines drawn across its border.
  EXPECT_NEAR(without.surface, with.surface, 0.03 * with.surface);
  nlohmann::json report{{"faces", mesh.num_faces()}};
  const ParamQuality q = [&] {
    ParamQuality r;
    r.arap_per_face.assign(static_cast<std::size_t>(mesh.num_faces()), 0.1);
    return r;
  }();
  write_pipeline_report((dir / "r.html").string(), "bunny", mesh, &p, nullptr, report, &q);
  const std::string page = read_file_bytes((dir / "r.html").string());
  EXPECT_NE(page.find("ARAP energy per triangle"), std::string::npos);
  EXPECT_NE(page.find("\"uv\":["), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace quadcover
