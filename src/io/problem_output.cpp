// The [output] section of a problem file: snapshots, and what the picture of the final state shows.
#include <cmath>

#include "latfrac/scene/picture_options.h"
#include "problem_reader.h"

namespace latfrac::problem {
namespace {

void read_snapshots(const Section& s, Scene& scene) {
  const double total = scene.loading.total;
  const Range between{std::min(0.0, total), std::max(0.0, total), false, false,
                      "strain, between 0 and loading.total"};
  scene.output.snapshots =
      s.numbers("snapshots", between, 0, "[lambda, ...]").value_or(std::vector<double>{});
  const std::vector<double>& snapshots = scene.output.snapshots;
  for (std::size_t i = 1; i < snapshots.size(); ++i) {
    if (std::abs(snapshots[i]) <= std::abs(snapshots[i - 1])) {
      s.fail("snapshots",
             "are not in loading order (" + format_number(snapshots[i - 1]) + " then " +
                 format_number(snapshots[i]) + ")",
             "allowed: strains in the order loading reaches them, each once");
    }
  }
}

// section_y or section_x: a 3-D block's reference coordinate, inside the block.
void read_section(const Section& s, const LatticeSpec& lattice, PictureOptions& picture) {
  const bool y = s.has("section_y"), x = s.has("section_x");
  if (!x && !y) return;
  const std::string_view key = y ? "section_y" : "section_x";
  if (x && y) s.fail("section_x", "is given with section_y", "allowed: one of the two");
  if (lattice.dim != 3)
    s.fail(key, "only applies in 3-D (a 2-D run is one section)",
           "allowed: remove it, or set lattice.dim = 3");
  if (picture.view != PictureView::section)
    s.fail(key,
           "chooses the plane of a section view; picture_view \"" +
               std::string(name_of(picture.view)) + "\" draws the whole block",
           "allowed: picture_view = \"section\", or remove it");
  const double extent = lattice.size[y ? 1 : 0];
  picture.section_axis = y ? SectionAxis::y : SectionAxis::x;
  picture.section_at = s.number(key, {0, extent, false, false, "m, inside the block"});
}

void read_picture(const Section& s, const LatticeSpec& lattice, Output& output) {
  PictureOptions& picture = output.picture_options;
  output.picture_format =
      picture_format_names()[s.choice("picture_format", picture_format_names()).value_or(0)];
  picture.view = static_cast<PictureView>(s.choice("picture_view", picture_view_names()).value_or(0));
  if (picture.view != PictureView::section && lattice.dim != 3)
    s.fail("picture_view", "\"" + std::string(name_of(picture.view)) + "\" needs a 3-D block",
           "allowed: \"section\" when lattice.dim = 2");
  picture.style = static_cast<CrackStyle>(s.choice("picture_style", crack_style_names()).value_or(0));
  picture.field = static_cast<NodeField>(s.choice("picture_field", node_field_names()).value_or(0));
  picture.faults = s.boolean("picture_faults").value_or(false);
  picture.width = static_cast<int>(s.integer("picture_width", 200, 20000).value_or(picture.width));
  read_section(s, lattice, picture);
}

}  // namespace

void read_output(const Section& top, Scene& scene) {
  const auto s = top.section(
      "output", {"snapshots", "exaggeration", "picture", "picture_format", "picture_view",
                 "picture_style", "picture_field", "picture_faults", "picture_width", "section_y",
                 "section_x"});
  if (!s) return;
  read_snapshots(*s, scene);
  // Bounded so that an exaggerated motion stays a finite number (1e308 failed in the
  // picture, after the whole run).
  scene.output.exaggeration =
      s->number("exaggeration", {0, max_exaggeration, false, false, ""}, 1.0);
  scene.output.picture = s->boolean("picture").value_or(true);
  read_picture(*s, scene.lattice, scene.output);
}

}  // namespace latfrac::problem
