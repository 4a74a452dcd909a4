// Small lattices with known broken bonds, and a PNG reader, for the picture tests.
#pragma once

#include <cairo.h>
#include <unistd.h>

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "latfrac/fracture/run_result.h"

namespace latfrac::testing {

inline constexpr double render_spacing = 1000.0;  // m

struct Rgb {
  int r = 0, g = 0, b = 0;
  bool operator==(const Rgb&) const = default;
  bool white() const { return r == 255 && g == 255 && b == 255; }
};

inline std::ostream& operator<<(std::ostream& out, const Rgb& c) {
  return out << "(" << c.r << ", " << c.g << ", " << c.b << ")";
}

// A PNG read with Cairo: pixel (x, y) covers [x, x + 1) x [y, y + 1) of the picture.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint32_t> pixels;  // 0xAARRGGBB, row-major

  Rgb at(int x, int y) const {
    const std::uint32_t p = pixels[static_cast<std::size_t>(y) * width + x];
    return {static_cast<int>((p >> 16) & 0xff), static_cast<int>((p >> 8) & 0xff),
            static_cast<int>(p & 0xff)};
  }
  // The pixel that holds the point (x, y).
  Rgb at_point(double x, double y) const {
    return at(static_cast<int>(std::floor(x)), static_cast<int>(std::floor(y)));
  }
};

inline Image read_png(const std::string& path) {
  cairo_surface_t* surface = cairo_image_surface_create_from_png(path.c_str());
  REQUIRE(cairo_surface_status(surface) == CAIRO_STATUS_SUCCESS);
  cairo_surface_flush(surface);
  Image image{cairo_image_surface_get_width(surface), cairo_image_surface_get_height(surface), {}};
  const int stride = cairo_image_surface_get_stride(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      image.pixels.push_back(*reinterpret_cast<const std::uint32_t*>(data + y * stride + 4 * x));
  cairo_surface_destroy(surface);
  return image;
}

// Nearest-neighbour bonds (reference length within 1% of the spacing).
inline void add_nearest_bonds(RunResult& result) {
  const std::size_t n = result.node_count();
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) {
      const double* p = &result.positions[3 * a];
      const double* q = &result.positions[3 * b];
      if (std::abs(std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) - render_spacing) <
          0.01 * render_spacing) {
        result.bonds.insert(result.bonds.end(), {std::int64_t(a), std::int64_t(b)});
        result.bond_kind.push_back(0);
      }
    }
}

inline void add_snapshot(RunResult& result, double lambda) {
  Snapshot snapshot;
  snapshot.lambda = lambda;
  snapshot.displacement.assign(3 * result.node_count(), 0.0);
  snapshot.bond_intact.assign(result.bond_count(), 1);
  snapshot.bond_failure_index.assign(result.bond_count(), 0.0);
  snapshot.node_stress.assign(6 * result.node_count(), 0.0);
  result.snapshots.push_back(snapshot);
}

// A triangular patch of columns x rows nodes in the x-z plane: node (i, k) is
// i + columns k, at x = (i + k/2 mod 1) a, z = k a sqrt(3)/2.
inline RunResult triangular_patch(int columns = 10, int rows = 6) {
  RunResult result;
  result.scene = {"patch-2d", 2, render_spacing, "elliptic", 1.0, ""};
  for (int k = 0; k < rows; ++k)
    for (int i = 0; i < columns; ++i)
      result.positions.insert(result.positions.end(), {(i + 0.5 * (k % 2)) * render_spacing, 0.0,
                                                       k * render_spacing * std::sqrt(3.0) / 2});
  add_nearest_bonds(result);
  add_snapshot(result, 0.01);
  return result;
}

// A cubic block of 10 x 3 x 6 nodes; node (i, j, k) is i + 10 j + 30 k at (i, j, k) a.
inline RunResult cubic_block() {
  RunResult result;
  result.scene = {"block-3d", 3, render_spacing, "", 1.0, ""};
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 10; ++i)
        result.positions.insert(result.positions.end(),
                                {i * render_spacing, j * render_spacing, k * render_spacing});
  add_nearest_bonds(result);
  add_snapshot(result, 0.0);
  return result;
}

inline std::size_t bond_between(const RunResult& result, std::int64_t a, std::int64_t b) {
  for (std::size_t bond = 0; bond < result.bond_count(); ++bond)
    if ((result.bonds[2 * bond] == a && result.bonds[2 * bond + 1] == b) ||
        (result.bonds[2 * bond] == b && result.bonds[2 * bond + 1] == a))
      return bond;
  FAIL("no bond between nodes " << a << " and " << b);
  return 0;
}

// Breaks the bond between nodes a and b in every snapshot, with a break event of `mode`.
inline std::size_t break_bond(RunResult& result, std::int64_t a, std::int64_t b, std::int8_t mode) {
  const std::size_t bond = bond_between(result, a, b);
  for (Snapshot& snapshot : result.snapshots) snapshot.bond_intact[bond] = 0;
  result.events.push_back({0.0, static_cast<std::int64_t>(bond), 1.0, static_cast<BreakMode>(mode), 0});
  return bond;
}

// The midpoint of a bond at reference positions.
inline std::array<double, 3> bond_middle(const RunResult& result, std::size_t bond) {
  const double* p = &result.positions[3 * result.bonds[2 * bond]];
  const double* q = &result.positions[3 * result.bonds[2 * bond + 1]];
  return {(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2};
}

struct ScratchDir {
  std::filesystem::path path = std::filesystem::temp_directory_path() /
                               ("latfrac_render_test_" + std::to_string(getpid()));
  ScratchDir() { std::filesystem::create_directories(path); }
  ~ScratchDir() { std::filesystem::remove_all(path); }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

}  // namespace latfrac::testing
