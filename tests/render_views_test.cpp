// Tests of what pictures show: node fields and their colour bar, the colour map, 3-D
// sections at y and x, the surface map, the oblique view's depth cue, fitted faults.
#include <catch2/catch.hpp>
#include <set>
#include <string>

#include "colour_map.h"
#include "latfrac/analysis/fault_analysis.h"
#include "latfrac/base/error.h"
#include "latfrac/render/node_field.h"
#include "latfrac/render/render.h"
#include "render_scenes.h"

using namespace latfrac;
using namespace latfrac::testing;

namespace {

Rgb rgb(Colour c) { return {c.r, c.g, c.b}; }

PictureOptions with_field(NodeField field) {
  PictureOptions options;
  options.field = field;
  options.width = 800;
  return options;
}

// The distinct colours of the pixels at the nodes' deformed positions.
std::set<std::array<int, 3>> node_colours(const Image& image, const PictureReport& report,
                                          const RunResult& result) {
  std::set<std::array<int, 3>> colours;
  const Snapshot& snapshot = result.snapshots[0];
  for (std::size_t node = 0; node < result.node_count(); ++node) {
    const double* p = &result.positions[3 * node];
    const double* u = &snapshot.displacement[3 * node];
    const auto at = report.pixel_of({p[0] + u[0], p[1] + u[1], p[2] + u[2]});
    const Rgb c = image.at_point(at[0], at[1]);
    colours.insert({c.r, c.g, c.b});
  }
  return colours;
}

}  // namespace

TEST_CASE("the colour bar's end labels are the field's minimum and maximum", "[render]") {
  // The labels show 4 significant digits: equal within half a unit of the 4th.
  ScratchDir dir;
  RunResult result = triangular_patch();
  Snapshot& snapshot = result.snapshots[0];
  const double top = 5 * std::sqrt(3.0) / 2 * render_spacing;
  for (std::size_t node = 0; node < result.node_count(); ++node) {
    snapshot.displacement[3 * node] = 1e-3 * result.positions[3 * node];  // ux = 1e-3 x
    // Lithostatic: sigma_zz = -rho g (top - z), rho g = 26 kPa/m.
    snapshot.node_stress[6 * node + 2] = -26e3 * (top - result.positions[3 * node + 2]);
  }
  const PictureReport ux = render_picture(result, 0, dir.file("ux.png"), with_field(NodeField::ux));
  CHECK(std::stod(ux.colour_bar_low) == Approx(0).margin(1e-12));
  CHECK(std::stod(ux.colour_bar_high) == Approx(9.5).epsilon(5e-4));  // 1e-3 x 9.5 km, m
  const PictureReport zz =
      render_picture(result, 0, dir.file("zz.png"), with_field(NodeField::sigma_zz));
  CHECK(std::stod(zz.colour_bar_low) == Approx(-26e3 * top / 1e6).epsilon(5e-4));  // MPa
  CHECK(std::stod(zz.colour_bar_high) == Approx(0).margin(1e-12));

  // The map runs from dark at the minimum to light at the maximum.
  const Image image = read_png(dir.file("ux.png"));
  const auto left = ux.pixel_of({0, 0, 0}), right = ux.pixel_of({9 * render_spacing, 0, 0});
  CHECK(lab_of({static_cast<std::uint8_t>(image.at_point(left[0], left[1]).r),
                static_cast<std::uint8_t>(image.at_point(left[0], left[1]).g),
                static_cast<std::uint8_t>(image.at_point(left[0], left[1]).b)})
            .l < 40);
  CHECK(lab_of({static_cast<std::uint8_t>(image.at_point(right[0], right[1]).r),
                static_cast<std::uint8_t>(image.at_point(right[0], right[1]).g),
                static_cast<std::uint8_t>(image.at_point(right[0], right[1]).b)})
            .l > 80);
  CHECK(node_colours(image, ux, result).size() > 8);
}

TEST_CASE("a uniform field is drawn in one colour, its bar labelled with its value", "[render]") {
  ScratchDir dir;
  RunResult result = triangular_patch();
  for (std::size_t node = 0; node < result.node_count(); ++node)
    result.snapshots[0].node_stress[6 * node] = 30e6;  // uniaxial sigma_xx = 30 MPa
  // Uniaxial stress s: von Mises |s|, sqrt(J2) = |s| / sqrt(3), mean s / 3.
  const std::pair<NodeField, double> expected[] = {{NodeField::von_mises, 30},
                                                   {NodeField::sqrt_j2, 30 / std::sqrt(3.0)},
                                                   {NodeField::sigma_mean, 10},
                                                   {NodeField::sigma_xx, 30}};
  for (const auto& [field, value] : expected) {
    INFO("field " << name_of(field));
    const PictureReport report = render_picture(result, 0, dir.file("u.png"), with_field(field));
    CHECK(std::stod(report.colour_bar_low) == Approx(value).epsilon(5e-4));
    CHECK(std::stod(report.colour_bar_high) == Approx(value).epsilon(5e-4));
    const auto colours = node_colours(read_png(dir.file("u.png")), report, result);
    REQUIRE(colours.size() == 1);
    const auto only = *colours.begin();
    CHECK(Rgb{only[0], only[1], only[2]} != rgb(lattice_colour));
    CHECK_FALSE(Rgb{only[0], only[1], only[2]}.white());
  }
}

TEST_CASE("the colour map's lightness rises evenly from dark to light", "[render]") {
  double previous_l = -1, total = 0, smallest = 1e9, largest = 0;
  Lab previous = lab_of(field_colour(0));
  for (int i = 0; i <= 64; ++i) {
    const Lab lab = lab_of(field_colour(i / 64.0));
    CHECK(lab.l > previous_l);
    previous_l = lab.l;
    if (i == 0) continue;
    const double step = std::hypot(lab.l - previous.l, lab.a - previous.a, lab.b - previous.b);
    total += step, smallest = std::min(smallest, step), largest = std::max(largest, step);
    previous = lab;
  }
  CHECK(lab_of(field_colour(0)).l < 20);
  CHECK(lab_of(field_colour(1)).l > 85);
  // Perceptual uniformity: every step of 1/64 within a factor 2 of the mean step.
  CHECK(smallest > 0.5 * total / 64);
  CHECK(largest < 2.0 * total / 64);
  CHECK(rgb(field_colour(std::nan(""))) == rgb(no_value_colour));
}

TEST_CASE("the failure index of a node is its most loaded intact bond's", "[render]") {
  RunResult result = triangular_patch();
  Snapshot& snapshot = result.snapshots[0];
  snapshot.bond_failure_index[bond_between(result, 12, 13)] = 0.9;
  snapshot.bond_failure_index[bond_between(result, 12, 11)] = 0.4;
  snapshot.bond_failure_index[bond_between(result, 13, 14)] = 5.0;
  snapshot.bond_intact[bond_between(result, 13, 14)] = 0;  // broken: not counted
  const std::vector<double> f = node_field(result, snapshot, NodeField::failure_index);
  CHECK(f[12] == 0.9);
  CHECK(f[13] == 0.9);
  CHECK(f[0] == 0.0);
  snapshot.bond_failure_index.clear();
  CHECK_THROWS_AS(node_field(result, snapshot, NodeField::failure_index), InputError);
}

TEST_CASE("a 3-D section shows the layer at the chosen y or x", "[render]") {
  ScratchDir dir;
  RunResult result = cubic_block();
  const std::size_t in_middle = break_bond(result, 43, 44, 0);  // (3,1,1)-(4,1,1), y = a
  const auto middle = bond_middle(result, in_middle);
  for (const double y : {render_spacing, 0.0}) {
    PictureOptions options{.section_at = y};
    options.width = 800;
    const PictureReport report = render_picture(result, 0, dir.file("y.png"), options);
    const Image image = read_png(dir.file("y.png"));
    const auto at = report.pixel_of(middle);
    INFO("section y = " << y);
    if (y > 0)
      CHECK(image.at_point(at[0], at[1]) == rgb(tensile_colour));
    else
      CHECK(image.at_point(at[0], at[1]) != rgb(tensile_colour));
  }
  // Across y at x = 5 a: the bond (5,0,2)-(5,1,2), drawn at (y, z) = (a/2, 2a).
  const std::size_t across = break_bond(result, 65, 75, 1);
  PictureOptions options{.section_axis = SectionAxis::x, .section_at = 5 * render_spacing};
  options.width = 800;
  const PictureReport report = render_picture(result, 0, dir.file("x.png"), options);
  CHECK(report.right == std::array<double, 3>{0, 1, 0});
  const auto at = report.pixel_of(bond_middle(result, across));
  CHECK(read_png(dir.file("x.png")).at_point(at[0], at[1]) == rgb(shear_colour));

  options = {.section_at = 5000.0};  // y runs 0 .. 2 km
  CHECK_THROWS_WITH(render_picture(result, 0, dir.file("out.png"), options),
                    Catch::Contains("outside the block"));
  CHECK_FALSE(std::filesystem::exists(dir.file("out.png")));
  // A plane given to a view that draws the whole block was ignored without a word.
  for (const PictureView view : {PictureView::map, PictureView::oblique}) {
    options = {.view = view, .section_at = render_spacing};
    CHECK_THROWS_WITH(render_picture(result, 0, dir.file("out.png"), options),
                      Catch::Contains("choose the plane of a section view"));
    CHECK_FALSE(std::filesystem::exists(dir.file("out.png")));
  }
}

TEST_CASE("the map shows the top layer's broken bonds seen from above", "[render]") {
  ScratchDir dir;
  RunResult result = cubic_block();
  const std::size_t top = break_bond(result, 163, 164, 0);  // (3,1,5)-(4,1,5)
  const std::size_t bottom = break_bond(result, 16, 17, 0);  // (6,1,0)-(7,1,0)
  PictureOptions options{.view = PictureView::map};
  options.width = 800;
  const PictureReport report = render_picture(result, 0, dir.file("map.png"), options);
  const Image image = read_png(dir.file("map.png"));
  auto pixel = [&](std::size_t bond) {
    const auto m = bond_middle(result, bond);
    // Seen from above: h = x, v = y, whatever z.
    const auto& f = report.frame;
    const auto& w = report.window;
    return image.at_point(f[0] + (m[0] - w[0]) / (w[1] - w[0]) * (f[2] - f[0]),
                          f[3] - (m[1] - w[2]) / (w[3] - w[2]) * (f[3] - f[1]));
  };
  CHECK(pixel(top) == rgb(tensile_colour));
  CHECK(pixel(bottom) != rgb(tensile_colour));
  CHECK(report.broken_bonds_drawn == 1);
}

TEST_CASE("the oblique view draws every broken bond, far ones faded", "[render]") {
  ScratchDir dir;
  RunResult result = cubic_block();
  const std::size_t near = break_bond(result, 93, 94, 0);   // (3,0,3)-(4,0,3): front
  const std::size_t far = break_bond(result, 113, 114, 0);  // (3,2,3)-(4,2,3): back
  PictureOptions options{.view = PictureView::oblique};
  options.width = 800;
  const PictureReport report = render_picture(result, 0, dir.file("oblique.png"), options);
  const Image image = read_png(dir.file("oblique.png"));
  const auto a = report.pixel_of(bond_middle(result, near));
  const auto b = report.pixel_of(bond_middle(result, far));
  CHECK(report.broken_bonds_drawn == 2);
  const Rgb front = image.at_point(a[0], a[1]), back = image.at_point(b[0], b[1]);
  CHECK(front == rgb(tensile_colour));
  // The far bond: the same hue, lighter (towards the paper).
  CHECK(back != front);
  CHECK(back.r >= front.r);
  CHECK(back.g > front.g);
  CHECK(back.b > front.b);
  CHECK(back.r > back.g + 40);
}

TEST_CASE("a fitted fault is drawn along its fitted line", "[render]") {
  ScratchDir dir;
  RunResult result = triangular_patch(12, 8);
  for (int k = 0; k < 8; ++k) break_bond(result, 5 + 12 * k, 6 + 12 * k, 0);  // a vertical crack
  const FaultReport faults = analyze_faults(result, 0);
  REQUIRE(faults.faults.size() == 1);
  REQUIRE_FALSE(faults.faults[0].diffuse);
  PictureOptions options{.faults = true};
  options.width = 900;
  const PictureReport report = render_picture(result, 0, dir.file("faults.png"), options);
  const Image image = read_png(dir.file("faults.png"));
  // Along the fitted line through the centroid, perpendicular to the normal: ink where the
  // dashes are (two thirds of the way), nothing dark elsewhere on the crack.
  const Fault& fault = faults.faults[0];
  int dark = 0, samples = 0;
  for (double s = -2.5; s <= 2.5; s += 0.1, ++samples) {
    const std::array<double, 3> p{fault.centroid[0] + s * render_spacing * fault.normal[2], 0,
                                  fault.centroid[2] - s * render_spacing * fault.normal[0]};
    const auto at = report.pixel_of(p);
    const Rgb c = image.at_point(at[0], at[1]);
    dark += c.r < 90 && c.g < 90 && c.b < 90;
  }
  CHECK(dark > 0.4 * samples);
}
