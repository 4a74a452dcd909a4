// Tests of section pictures: broken bonds in their mode's colour where they are, the paper's
// particles, formats by extension (SVG paths, PDF header), bad options and failed writes.
#include "latfrac/render/render.h"

#include <expat.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <map>
#include <sstream>

#include "colour_map.h"
#include "latfrac/base/error.h"
#include "render_scenes.h"

namespace fs = std::filesystem;
using namespace latfrac;
using namespace latfrac::testing;

namespace {

Rgb rgb(Colour c) { return {c.r, c.g, c.b}; }

// Where the point (h, v) of the picture plane lands: the frame shows the window, linearly.
std::array<double, 2> pixel_in_frame(const PictureReport& report, double h, double v) {
  const auto& f = report.frame;
  const auto& w = report.window;
  return {f[0] + (h - w[0]) / (w[1] - w[0]) * (f[2] - f[0]),
          f[3] - (v - w[2]) / (w[3] - w[2]) * (f[3] - f[1])};
}

Rgb colour_at(const Image& image, const PictureReport& report, double h, double v) {
  const auto [x, y] = pixel_in_frame(report, h, v);
  return image.at_point(x, y);
}

// A patch with a tensile, a shear and a pre-cut bond broken, far from each other.
RunResult patch_with_three_modes(std::size_t bonds[3]) {
  RunResult result = triangular_patch();
  bonds[0] = break_bond(result, 12, 13, 0);  // (2, 1)-(3, 1)
  bonds[1] = break_bond(result, 36, 37, 1);  // (6, 3)-(7, 3)
  bonds[2] = break_bond(result, 48, 49, 2);  // (8, 4)-(9, 4)
  return result;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The <path> elements of an SVG, counted by stroke colour (as 0-255 channels).
struct SvgPaths {
  std::map<std::array<int, 3>, int> strokes;
  int elements = 0;
};

void XMLCALL on_element(void* data, const XML_Char* name, const XML_Char** attributes) {
  SvgPaths& paths = *static_cast<SvgPaths*>(data);
  if (std::string(name) != "path") return;
  ++paths.elements;
  for (int i = 0; attributes[i]; i += 2) {
    const std::string value = attributes[i + 1];
    const std::size_t at = value.find("stroke:rgb(");
    if (std::string(attributes[i]) != "style" || at == std::string::npos) continue;
    double r = 0, g = 0, b = 0;
    REQUIRE(std::sscanf(value.c_str() + at, "stroke:rgb(%lf%%,%lf%%,%lf%%)", &r, &g, &b) == 3);
    ++paths.strokes[{static_cast<int>(std::lround(r * 2.55)),
                     static_cast<int>(std::lround(g * 2.55)),
                     static_cast<int>(std::lround(b * 2.55))}];
  }
}

SvgPaths parse_svg(const std::string& text) {
  SvgPaths paths;
  XML_Parser parser = XML_ParserCreate(nullptr);
  XML_SetUserData(parser, &paths);
  XML_SetStartElementHandler(parser, on_element);
  const bool parsed =
      XML_Parse(parser, text.data(), static_cast<int>(text.size()), 1) == XML_STATUS_OK;
  INFO("expat: " << XML_ErrorString(XML_GetErrorCode(parser)) << " at line "
                 << XML_GetCurrentLineNumber(parser));
  XML_ParserFree(parser);
  REQUIRE(parsed);
  return paths;
}

}  // namespace

TEST_CASE("a broken bond's midpoint is drawn in its mode's colour, the lattice grey", "[render]") {
  ScratchDir dir;
  std::size_t bonds[3];
  const RunResult result = patch_with_three_modes(bonds);
  const PictureReport report = render_picture(result, 0, dir.file("cracks.png"), {.width = 800});
  const Image image = read_png(dir.file("cracks.png"));
  REQUIRE(image.width == 800);
  CHECK(image.height == report.height);
  // Equal scales on x and z.
  CHECK((report.frame[2] - report.frame[0]) / (report.window[1] - report.window[0]) ==
        Approx((report.frame[3] - report.frame[1]) / (report.window[3] - report.window[2]))
            .epsilon(1e-9));
  const Colour expected[3] = {tensile_colour, shear_colour, precut_colour};
  for (int mode = 0; mode < 3; ++mode) {
    const auto middle = bond_middle(result, bonds[mode]);
    INFO("mode " << mode);
    CHECK(colour_at(image, report, middle[0], middle[2]) == rgb(expected[mode]));
  }
  // A node far from every broken bond: (4, 2), at x = 4 a, z = sqrt(3) a.
  CHECK(colour_at(image, report, 4 * render_spacing, std::sqrt(3.0) * render_spacing) ==
        rgb(lattice_colour));
  CHECK(report.broken_bonds_drawn == 3);
}

TEST_CASE("min_offset draws only the broken bonds whose nodes moved apart by that much",
          "[render]") {
  // The tensile bond's right node moves 30 m away from its left one, the shear bond's
  // 3 m; the pre-cut's not at all. At 10 m only the first is drawn: the others' midpoints
  // are not drawn in their colours.
  ScratchDir dir;
  std::size_t bonds[3];
  RunResult result = patch_with_three_modes(bonds);
  result.snapshots[0].displacement[3 * 13] = 30.0;
  result.snapshots[0].displacement[3 * 37 + 2] = -3.0;
  PictureOptions options{.width = 800};
  options.min_offset = 10.0;
  const PictureReport report = render_picture(result, 0, dir.file("moved.png"), options);
  CHECK(report.broken_bonds_drawn == 1);
  const Image image = read_png(dir.file("moved.png"));
  const auto tensile = bond_middle(result, bonds[0]);
  const auto shear = bond_middle(result, bonds[1]);
  CHECK(colour_at(image, report, tensile[0] + 15.0, tensile[2]) == rgb(tensile_colour));
  CHECK(colour_at(image, report, shear[0], shear[2] - 1.5) != rgb(shear_colour));
  options.min_offset = 3.0;  // the shear bond's 3 m is enough
  CHECK(render_picture(result, 0, dir.file("moved3.png"), options).broken_bonds_drawn == 2);
  options.min_offset = 0;
  CHECK(render_picture(result, 0, dir.file("all.png"), options).broken_bonds_drawn == 3);
}

TEST_CASE("a compression run's broken bonds are drawn in their modes' colours too", "[render]") {
  // Its lambda falls from 0: the events before the snapshot at -0.01 are at -0.005 (and
  // the pre-cut's at 0). They were drawn as bonds without a break event.
  ScratchDir dir;
  std::size_t bonds[3];
  RunResult result = patch_with_three_modes(bonds);
  result.snapshots[0].lambda = -0.01;
  result.summary.final_lambda = -0.01;
  result.events[0].lambda = result.events[1].lambda = -0.005;
  const PictureReport report =
      render_picture(result, 0, dir.file("compressed.png"), {.width = 800});
  const Image image = read_png(dir.file("compressed.png"));
  const Colour expected[3] = {tensile_colour, shear_colour, precut_colour};
  for (int mode = 0; mode < 3; ++mode) {
    const auto middle = bond_middle(result, bonds[mode]);
    INFO("mode " << mode);
    CHECK(colour_at(image, report, middle[0], middle[2]) == rgb(expected[mode]));
  }
}

TEST_CASE("the particles style draws the nodes of broken bonds red, the others grey", "[render]") {
  ScratchDir dir;
  RunResult result = triangular_patch();
  break_bond(result, 12, 13, 0);
  PictureOptions options{.style = CrackStyle::particles};
  options.width = 800;
  const PictureReport report = render_picture(result, 0, dir.file("particles.png"), options);
  const Image image = read_png(dir.file("particles.png"));
  const double z1 = std::sqrt(3.0) / 2 * render_spacing;
  CHECK(colour_at(image, report, 2.5 * render_spacing, z1) == rgb(broken_particle_colour));
  CHECK(colour_at(image, report, 3.5 * render_spacing, z1) == rgb(broken_particle_colour));
  CHECK(colour_at(image, report, 5.5 * render_spacing, z1) == rgb(particle_colour));
  CHECK(report.broken_bonds_drawn == 0);
}

TEST_CASE("an intact lattice of particles shows no white line, however small its dots",
          "[render]") {
  // White inside the lattice means open bonds. With dots a few pixels apart, gaps under a
  // pixel wide once fell on the same pixel rows and drew white lines like cracks.
  ScratchDir dir;
  const RunResult result = triangular_patch(60, 40);
  for (int width = 300; width <= 1400; width += 50) {
    PictureOptions options{.style = CrackStyle::particles};
    options.width = width;
    const PictureReport report = render_picture(result, 0, dir.file("p.png"), options);
    const Image image = read_png(dir.file("p.png"));
    const double dot_spacing = (report.frame[2] - report.frame[0]) /
                               (report.window[1] - report.window[0]) * render_spacing;
    // The inside: two spacings in from the lattice's edges.
    const auto [x0, y1] = pixel_in_frame(report, 2 * render_spacing, 2 * render_spacing);
    const auto [x1, y0] = pixel_in_frame(report, 57 * render_spacing, 31 * render_spacing);
    int longest = 0, white = 0;
    for (int y = static_cast<int>(y0); y <= static_cast<int>(y1); ++y)
      for (int x = static_cast<int>(x0), run = 0; x <= static_cast<int>(x1); ++x) {
        run = image.at(x, y).white() ? run + 1 : 0;
        white += run > 0;
        longest = std::max(longest, run);
      }
    INFO("width " << width << " px, dots " << dot_spacing << " px apart");
    if (dot_spacing < 9.5) {
      CHECK(white == 0);  // drawn solid
    } else if (dot_spacing > 10.5) {
      CHECK(white > 0);  // a gap at each bond, never as long as a particle
      CHECK(longest < 0.8 * dot_spacing);
    }
  }
}

TEST_CASE("the exaggeration moves the drawn lattice by u times the factor", "[render]") {
  ScratchDir dir;
  RunResult result = triangular_patch();
  const std::size_t bond = break_bond(result, 0, 1, 0);  // at the left edge
  for (std::size_t node = 0; node < result.node_count(); ++node)
    result.snapshots[0].displacement[3 * node] = 2 * render_spacing;
  for (const double factor : {0.0, 1.0, 2.5}) {
    PictureOptions options;
    options.width = 800, options.exaggeration = factor;
    const PictureReport report = render_picture(result, 0, dir.file("e.png"), options);
    const Image image = read_png(dir.file("e.png"));
    const auto middle = bond_middle(result, bond);
    INFO("exaggeration " << factor);
    CHECK(colour_at(image, report, middle[0] + factor * 2 * render_spacing, middle[2]) ==
          rgb(tensile_colour));
    // The window holds the reference and the deformed lattice.
    CHECK(report.window[0] < 0);
    CHECK(report.window[1] > (9.5 + 2 * factor) * render_spacing);
  }
}

TEST_CASE("an exaggeration that moves the nodes beyond ten sizes of the lattice is noted",
          "[render]") {
  // The patch spans 9.5 spacings in x (9500 m); every node moves 2000 m. The note starts
  // where the motion passes 10 x 9500 m, at a factor of 47.5, and names the factor that
  // makes the motion a fifth of the size: 0.2 x 9500 / 2000 = 0.95.
  ScratchDir dir;
  RunResult result = triangular_patch();
  for (std::size_t node = 0; node < result.node_count(); ++node)
    result.snapshots[0].displacement[3 * node] = 2 * render_spacing;
  PictureOptions options;
  options.width = 400;
  options.exaggeration = 47;
  CHECK(render_picture(result, 0, dir.file("n.png"), options).note.empty());
  options.exaggeration = 48;
  const std::string note = render_picture(result, 0, dir.file("n.png"), options).note;
  CHECK_THAT(note, Catch::Contains("9.6e+04 m") && Catch::Contains("about 0.95 fits"));
}

TEST_CASE("an SVG parses as XML and holds one stroked path per broken bond", "[render]") {
  ScratchDir dir;
  std::size_t bonds[3];
  RunResult result = patch_with_three_modes(bonds);
  break_bond(result, 14, 15, 0);  // a second tensile bond
  render_picture(result, 0, dir.file("cracks.svg"), {.width = 800});
  const SvgPaths paths = parse_svg(read_text(dir.file("cracks.svg")));
  auto strokes_of = [&](Colour c) {
    const auto found = paths.strokes.find({c.r, c.g, c.b});
    return found == paths.strokes.end() ? 0 : found->second;
  };
  CHECK(strokes_of(tensile_colour) == 2);
  CHECK(strokes_of(shear_colour) == 1);
  CHECK(strokes_of(precut_colour) == 1);
  CHECK(paths.elements > 4);  // and the lattice, frame and text
}

TEST_CASE("a PDF starts with %PDF, and the format follows the extension in any case", "[render]") {
  ScratchDir dir;
  const RunResult result = triangular_patch();
  render_picture(result, 0, dir.file("picture.PDF"));
  CHECK(read_text(dir.file("picture.PDF")).rfind("%PDF-", 0) == 0);
  CHECK(picture_format_of("a.Svg") == PictureFormat::svg);
  CHECK(picture_format_of("dir.png/a.png") == PictureFormat::png);
}

TEST_CASE("bad options are input errors and write no file", "[render]") {
  ScratchDir dir;
  const RunResult result = triangular_patch();
  auto refused = [&](const std::string& name, const PictureOptions& options,
                     const RunResult& drawn) {
    INFO(name);
    CHECK_THROWS_AS(render_picture(drawn, 0, dir.file(name), options), InputError);
    CHECK_FALSE(fs::exists(dir.file(name)));
    CHECK_FALSE(fs::exists(dir.file(name) + ".partial"));
  };
  refused("picture.jpg", {}, result);
  refused("picture", {}, result);
  refused("map.png", {.view = PictureView::map}, result);
  refused("oblique.png", {.view = PictureView::oblique}, result);
  refused("section.png", {.section_at = 0.0}, result);  // 2-D: one section
  refused("narrow.png", {.width = 50}, result);
  refused("negative-offset.png", {.min_offset = -1.0}, result);
  refused("nan-offset.png", {.min_offset = std::numeric_limits<double>::quiet_NaN()}, result);
  CHECK_THROWS_AS(render_picture(result, 1, dir.file("none.png")), InputError);
  RunResult short_of_data = result;
  short_of_data.snapshots[0].displacement.pop_back();
  refused("short.png", {}, short_of_data);
  CHECK(fs::is_empty(dir.path));
}

TEST_CASE("a failed write throws and leaves no file", "[render]") {
  ScratchDir dir;
  std::ofstream(dir.file("a_file")) << "not a directory\n";
  for (const std::string name :
       {"a_file/picture.png", "a_file/picture.svg", "a_file/sub/picture.pdf"}) {
    const std::string path = dir.file(name);
    INFO(name);
    CHECK_THROWS_WITH(render_picture(triangular_patch(), 0, path),
                      Catch::Contains("cannot create output directory '" + dir.file("a_file")));
    CHECK_FALSE(fs::exists(path));
    CHECK_FALSE(fs::exists(path + ".partial"));
  }
  CHECK(read_text(dir.file("a_file")) == "not a directory\n");
}

TEST_CASE("a picture's missing folders are made, as run -o makes its own", "[render]") {
  ScratchDir dir;
  const std::string path = dir.file("figures/sections/picture.png");
  render_picture(triangular_patch(), 0, path);
  CHECK(fs::is_regular_file(path));
  CHECK(fs::file_size(path) > 0);
  CHECK_FALSE(fs::exists(path + ".partial"));
}

TEST_CASE("snapshot_nearest picks the nearest lambda, the last for NaN", "[render]") {
  RunResult result = triangular_patch();
  CHECK_THROWS_AS(snapshot_nearest(RunResult{}, 0.0), InputError);
  result.snapshots[0].lambda = 0.01;
  add_snapshot(result, 0.02);
  add_snapshot(result, 0.04);
  CHECK(snapshot_nearest(result, -1.0) == 0);
  CHECK(snapshot_nearest(result, 0.012) == 0);
  CHECK(snapshot_nearest(result, 0.016) == 1);
  CHECK(snapshot_nearest(result, 0.031) == 2);
  CHECK(snapshot_nearest(result, std::nan("")) == 2);
  // Far beyond the range, where the distances round to one value: still the nearest end.
  CHECK(snapshot_nearest(result, 1e15) == 2);
  CHECK(snapshot_nearest(result, 1e308) == 2);
  CHECK(snapshot_nearest(result, -1e308) == 0);
  // A compression run's snapshots go down: the ends are found by value, not position.
  for (auto& snapshot : result.snapshots) snapshot.lambda = -snapshot.lambda;
  CHECK(snapshot_nearest(result, -1e15) == 2);
  CHECK(snapshot_nearest(result, 1e15) == 0);
  CHECK(snapshot_nearest(result, -0.016) == 1);
}
