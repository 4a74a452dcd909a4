// Tests of the cross-section pictures: size, red exactly at broken bonds, 3-D slice, I/O.
#include "latfrac/render/render.h"

#include <png.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "bitmap_font.h"
#include "latfrac/base/error.h"
#include "raster.h"

namespace fs = std::filesystem;
using namespace latfrac;

namespace {

constexpr double spacing = 1000.0;  // m

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;

  const std::uint8_t* at(int x, int y) const { return &rgb[(std::size_t(y) * width + x) * 3]; }
};

Image read_png(const std::string& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  REQUIRE(png_image_begin_read_from_file(&image, path.c_str()) != 0);
  image.format = PNG_FORMAT_RGB;
  Image result{static_cast<int>(image.width), static_cast<int>(image.height),
               std::vector<std::uint8_t>(PNG_IMAGE_SIZE(image))};
  REQUIRE(png_image_finish_read(&image, nullptr, result.rgb.data(), 0, nullptr) != 0);
  return result;
}

struct Box {
  int x0 = std::numeric_limits<int>::max(), y0 = x0, x1 = -1, y1 = -1;
  long pixels = 0;

  void add(int x, int y) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
    ++pixels;
  }
  double centre_x() const { return 0.5 * (x0 + x1); }
  double centre_y() const { return 0.5 * (y0 + y1); }
};

bool is_red(const std::uint8_t* p) { return p[0] > 180 && p[1] < 80 && p[2] < 80; }
// The dots' grey, told apart from the near-black of frame and text.
bool is_node_grey(const std::uint8_t* p) {
  return p[0] == p[1] && p[1] == p[2] && p[0] > 60 && p[0] < 160;
}

Box box_of(const Image& image, bool (*wanted)(const std::uint8_t*)) {
  Box box;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (wanted(image.at(x, y))) box.add(x, y);
  return box;
}

// Nearest-neighbour bonds (reference length within 1% of the spacing).
void add_nearest_bonds(RunResult& result) {
  const std::size_t n = result.node_count();
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) {
      const double* p = &result.positions[3 * a];
      const double* q = &result.positions[3 * b];
      if (std::abs(std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) - spacing) < 0.01 * spacing) {
        result.bonds.insert(result.bonds.end(), {std::int64_t(a), std::int64_t(b)});
        result.bond_kind.push_back(0);
      }
    }
}

void add_snapshot(RunResult& result, double lambda) {
  Snapshot snapshot;
  snapshot.lambda = lambda;
  snapshot.displacement.assign(3 * result.node_count(), 0.0);
  snapshot.bond_intact.assign(result.bond_count(), 1);
  snapshot.bond_failure_index.assign(result.bond_count(), 0.0);
  snapshot.node_stress.assign(6 * result.node_count(), 0.0);
  result.snapshots.push_back(snapshot);
}

// A triangular patch of columns x rows nodes in the x-z plane: node (i, k) is
// i + columns k.
RunResult triangular_patch(int columns = 10, int rows = 6) {
  RunResult result;
  result.scene = {"patch-2d", 2, spacing, "elliptic", 1.0};
  for (int k = 0; k < rows; ++k)
    for (int i = 0; i < columns; ++i)
      result.positions.insert(result.positions.end(), {(i + 0.5 * (k % 2)) * spacing, 0.0,
                                                       k * spacing * std::sqrt(3.0) / 2});
  add_nearest_bonds(result);
  add_snapshot(result, 0.01);
  return result;
}

// A cubic block of 10 x 3 x 6 nodes; node (i, j, k) is i + 10 j + 30 k, layer j at y = j a.
RunResult cubic_block() {
  RunResult result;
  result.scene = {"block-3d", 3, spacing, "", 1.0};
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 10; ++i)
        result.positions.insert(result.positions.end(), {i * spacing, j * spacing, k * spacing});
  add_nearest_bonds(result);
  add_snapshot(result, 0.0);
  return result;
}

std::size_t bond_between(const RunResult& result, std::int64_t a, std::int64_t b) {
  for (std::size_t bond = 0; bond < result.bond_count(); ++bond)
    if ((result.bonds[2 * bond] == a && result.bonds[2 * bond + 1] == b) ||
        (result.bonds[2 * bond] == b && result.bonds[2 * bond + 1] == a))
      return bond;
  FAIL("no bond between nodes " << a << " and " << b);
  return 0;
}

struct ScratchDir {
  fs::path path = fs::temp_directory_path() / ("latfrac_render_test_" + std::to_string(getpid()));
  ScratchDir() { fs::create_directories(path); }
  ~ScratchDir() { fs::remove_all(path); }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

Image render(const RunResult& result, const ScratchDir& dir, const RenderOptions& options = {}) {
  const std::string path = dir.file("picture.png");
  render_png(result, 0, path, options);
  return read_png(path);
}

}  // namespace

TEST_CASE("an intact 2-D patch has the requested width, a plausible height, no red", "[render]") {
  ScratchDir dir;
  const Image image = render(triangular_patch(), dir, {800, -1});
  CHECK(image.width == 800);
  // The patch is 9.5 a wide and 4.3 a tall: the plot is about half as tall as wide.
  CHECK(image.height > 0.3 * image.width);
  CHECK(image.height < 0.9 * image.width);
  CHECK(box_of(image, is_red).pixels == 0);
  CHECK(box_of(image, is_node_grey).pixels > 60);
  CHECK_FALSE(fs::exists(dir.file("picture.png.partial")));
}

TEST_CASE("an intact lattice shows no white line, however small its dots", "[render]") {
  // White inside the lattice means open bonds. With dots a few pixels apart, gaps under a
  // pixel wide once fell on the same pixel rows and drew white lines like cracks.
  ScratchDir dir;
  const RunResult result = triangular_patch(60, 40);
  for (int width = 300; width <= 1400; width += 25) {
    const Image image = render(result, dir, {width, -1});
    const Box lattice = box_of(image, is_node_grey);
    const double dot_spacing = (lattice.x1 - lattice.x0) / 59.5;  // about: dots overhang
    // The inside: a margin of two spacings from the lattice's edges.
    const int x0 = lattice.x0 + static_cast<int>(2 * dot_spacing),
              x1 = lattice.x1 - static_cast<int>(2 * dot_spacing);
    const int y0 = lattice.y0 + static_cast<int>(2 * dot_spacing),
              y1 = lattice.y1 - static_cast<int>(2 * dot_spacing);
    int longest = 0, white = 0;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0, run = 0; x <= x1; ++x) {
        const bool is_white = image.at(x, y)[0] == 255 && image.at(x, y)[1] == 255;
        run = is_white ? run + 1 : 0;
        white += is_white;
        longest = std::max(longest, run);
      }
    INFO("width " << width << " px, dots " << dot_spacing << " px apart");
    if (dot_spacing < 9.5) {
      CHECK(white == 0);  // drawn solid
    } else if (dot_spacing > 10.5) {
      // Particles with a gap of a pixel or more at each bond: no pixel row runs white
      // past a whole particle.
      CHECK(white > 0);
      CHECK(longest < 0.8 * dot_spacing);
    }
  }
}

TEST_CASE("nodes of a broken bond are red, where the bond is", "[render]") {
  ScratchDir dir;
  RunResult result = triangular_patch();
  // Nodes (2, 1) and (3, 1): x = 2.5 a and 3.5 a of 0 .. 9.5 a, z = 0.87 a of 0 .. 4.33 a.
  result.snapshots[0].bond_intact[bond_between(result, 12, 13)] = 0;
  const Image image = render(result, dir);
  const Box red = box_of(image, is_red);
  REQUIRE(red.pixels > 0);
  Box dots = box_of(image, is_node_grey);
  dots.add(red.x0, red.y0), dots.add(red.x1, red.y1);
  // Dot centres span the dots' box less one dot radius on each side.
  const double radius = 0.5 * (red.y1 - red.y0);
  const double fraction_x = (red.centre_x() - dots.x0 - radius) / (dots.x1 - dots.x0 - 2 * radius);
  const double fraction_up = (dots.y1 - radius - red.centre_y()) / (dots.y1 - dots.y0 - 2 * radius);
  CHECK(fraction_x == Approx(3.0 / 9.5).margin(0.03));
  CHECK(fraction_up == Approx(0.2).margin(0.03));
  // Two dots side by side: twice as wide as tall, about one spacing apart.
  CHECK(red.x1 - red.x0 > 1.5 * (red.y1 - red.y0));
}

TEST_CASE("a 3-D result is drawn as its middle y layer", "[render]") {
  ScratchDir dir;
  RunResult outer = cubic_block();
  outer.snapshots[0].bond_intact[bond_between(outer, 33, 34)] = 0;  // layer y = 0
  CHECK(box_of(render(outer, dir), is_red).pixels == 0);

  RunResult middle = cubic_block();
  middle.snapshots[0].bond_intact[bond_between(middle, 43, 44)] = 0;  // layer y = a
  const Image image = render(middle, dir);
  CHECK(box_of(image, is_red).pixels > 0);

  RunResult across = cubic_block();
  across.snapshots[0].bond_intact[bond_between(across, 33, 43)] = 0;  // y = 0 to y = a
  CHECK(box_of(render(across, dir), is_red).pixels > 0);

  // The same picture as the middle layer alone, drawn as a 2-D section.
  RunResult layer;
  layer.scene = {"layer", 2, spacing, "", 1.0};
  for (std::size_t node = 0; node < middle.node_count(); ++node)
    if (middle.positions[3 * node + 1] == spacing)
      layer.positions.insert(layer.positions.end(),
                             {middle.positions[3 * node], 0.0, middle.positions[3 * node + 2]});
  add_nearest_bonds(layer);
  add_snapshot(layer, 0.0);
  CHECK(box_of(image, is_node_grey).pixels + box_of(image, is_red).pixels ==
        box_of(render(layer, dir), is_node_grey).pixels);
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
  CHECK(snapshot_nearest(result, 1.0) == 2);
  CHECK(snapshot_nearest(result, std::nan("")) == 2);
}

TEST_CASE("the exaggeration moves the dots", "[render]") {
  ScratchDir dir;
  RunResult result = triangular_patch();
  result.snapshots[0].bond_intact[bond_between(result, 0, 1)] = 0;  // at the left edge
  for (std::size_t node = 0; node < result.node_count(); ++node)
    result.snapshots[0].displacement[3 * node] = 9.5 * spacing;  // the patch's width

  const Image still_image = render(result, dir, {800, 0.0});
  const Image moved_image = render(result, dir, {800, 1.0});
  const Box still = box_of(still_image, is_red);
  const Box moved = box_of(moved_image, is_red);
  // The frame holds the reference and the deformed patch side by side: the patch is drawn
  // at about half the scale, and its left edge moves by about a third of the picture.
  const double width_ratio = double(box_of(moved_image, is_node_grey).x1 - moved.x0) /
                             (box_of(still_image, is_node_grey).x1 - still.x0);
  CHECK(width_ratio > 0.45);
  CHECK(width_ratio < 0.65);
  CHECK(moved.centre_x() - still.centre_x() > 0.25 * 800);

  result.scene.exaggeration = 1.0;
  const Box from_scene = box_of(render(result, dir, {800, -1}), is_red);
  CHECK(from_scene.x0 == moved.x0);
  CHECK(from_scene.y0 == moved.y0);
}

TEST_CASE("a failed write throws and leaves no file", "[render]") {
  ScratchDir dir;
  const std::string path = dir.file("no_such_dir/picture.png");
  CHECK_THROWS_AS(render_png(triangular_patch(), 0, path), Error);
  CHECK_FALSE(fs::exists(path));
  CHECK_FALSE(fs::exists(path + ".partial"));
}

TEST_CASE("inconsistent results and options are input errors", "[render]") {
  ScratchDir dir;
  const std::string path = dir.file("picture.png");
  RunResult result = triangular_patch();
  CHECK_THROWS_AS(render_png(result, 1, path), InputError);
  CHECK_THROWS_AS(render_png(result, 0, path, {50, -1}), InputError);
  result.snapshots[0].displacement.pop_back();
  CHECK_THROWS_AS(render_png(result, 0, path), InputError);
  CHECK_FALSE(fs::exists(path));
}

TEST_CASE("the font has a distinct glyph for every character the pictures use", "[render]") {
  const std::string characters =
      "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz.,-+=:()/_";
  const Glyph& missing = glyph_for('\x01');
  std::set<std::vector<std::uint8_t>> seen;
  for (char c : characters) {
    const Glyph& glyph = glyph_for(c);
    INFO("character '" << c << "'");
    CHECK(glyph.rows != missing.rows);
    CHECK(seen.insert({glyph.rows.begin(), glyph.rows.end()}).second);
  }
  CHECK(text_width("x (km)", 2) == (6 * glyph_advance - 1) * 2);
}
