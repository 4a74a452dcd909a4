// Benchmark of the pictures: a 2-D 100k-node and a 3-D 50k-node snapshot drawn in each
// picture kind and format; prints the wall time of render_picture and the file size.
//
//   build/bench/bench_render               # both scenes, pictures in a temporary directory
//   build/bench/bench_render out/pictures  # ... kept in out/pictures (to look at them)
//
// The snapshots are made up, not run: a graben of two 60-degree faults from the surface
// (tensile and shear breaks) and a vertical pre-cut between them; lithostatic stress with
// a horizontal tension; the graben block lowered by 200 m, the walls pulled apart by 1 %.
// The "shattered" 2-D snapshot has every tenth bond broken besides (32k segments).

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "latfrac/geometry/lattice.h"
#include "latfrac/render/render.h"

using namespace latfrac;
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

RunResult made_up_snapshot(int dim, double spacing, bool shattered = false) {
  const double length = 60e3, width = 10e3, height = 30e3;
  const Lattice lattice = build_lattice({dim, spacing, {length, width, height}, true});
  RunResult result;
  result.scene = {std::string(dim == 2 ? "bench-2d" : "bench-3d") + (shattered ? "-shattered" : ""),
                  dim, spacing, "elliptic", 1.0, ""};
  for (const Vec3& p : lattice.positions) result.positions.insert(result.positions.end(), {p[0], p[1], p[2]});
  const double top = lattice.extent[2];
  // Two faults dipping 60 degrees towards x = 30 km, from 25 and 35 km at the surface.
  const double cot = 1 / std::tan(std::numbers::pi / 3);
  auto in_graben = [&](double x, double z) {
    const double depth = top - z;
    return x > 25e3 + depth * cot && x < 35e3 - depth * cot;
  };
  Snapshot snapshot;
  snapshot.lambda = 0.01;
  for (const Vec3& p : lattice.positions) {
    const double sigma_zz = -26e3 * (top - p[2]);
    snapshot.displacement.insert(snapshot.displacement.end(),
                                 {0.01 * (p[0] - length / 2), 0, in_graben(p[0], p[2]) ? -200.0 : 0.0});
    snapshot.node_stress.insert(snapshot.node_stress.end(),
                                {0.3 * sigma_zz + 20e6, 0.3 * sigma_zz, sigma_zz, 0, 1e6, 0});
  }
  for (std::size_t b = 0; b < lattice.bonds.size(); ++b) {
    const Bond& bond = lattice.bonds[b];
    result.bonds.insert(result.bonds.end(), {bond.i, bond.j});
    result.bond_kind.push_back(static_cast<std::int8_t>(bond.kind));
    const Vec3 middle = 0.5 * (lattice.positions[bond.i] + lattice.positions[bond.j]);
    const bool graben_edge =
        in_graben(lattice.positions[bond.i][0], lattice.positions[bond.i][2]) !=
        in_graben(lattice.positions[bond.j][0], lattice.positions[bond.j][2]);
    const bool precut = middle[2] > top - 5e3 && std::abs(middle[0] - 30e3) < spacing / 2 &&
                        (lattice.positions[bond.i][0] - 30e3) * (lattice.positions[bond.j][0] - 30e3) < 0;
    const bool across = graben_edge || (shattered && b % 10 == 3);
    snapshot.bond_intact.push_back(across || precut ? 0 : 1);
    snapshot.bond_failure_index.push_back(across || precut ? 1.0 : 0.5 * middle[2] / top);
    if (across || precut)
      result.events.push_back({precut ? 0.0 : 0.005, static_cast<std::int64_t>(b), 1.0,
                               precut ? BreakMode::precut : middle[2] > top / 2 ? BreakMode::tensile : BreakMode::shear, 0});
  }
  result.snapshots.push_back(snapshot);
  return result;
}

struct Case {
  std::string name;
  PictureOptions options;
  std::string extension;
};

void run_cases(const RunResult& result, const std::vector<Case>& cases, const fs::path& dir) {
  std::size_t broken = 0;
  for (std::uint8_t intact : result.snapshots[0].bond_intact) broken += intact == 0;
  std::printf("\n%s: %zu nodes, %zu bonds, %zu broken\n", result.scene.name.c_str(),
              result.node_count(), result.bond_count(), broken);
  std::printf("%-28s %8s %10s %10s\n", "picture", "seconds", "kB", "px");
  for (const Case& c : cases) {
    const fs::path path = dir / (result.scene.name + "-" + c.name + "." + c.extension);
    const auto start = Clock::now();
    const PictureReport report = render_picture(result, 0, path.string(), c.options);
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::printf("%-28s %8.2f %10.0f %5d x %d\n", (c.name + "." + c.extension).c_str(), seconds,
                fs::file_size(path) / 1024.0, report.width, report.height);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const bool keep = argc > 1;
  const fs::path dir = keep ? fs::path(argv[1]) : fs::temp_directory_path() / "latfrac_bench_render";
  fs::create_directories(dir);

  PictureOptions cracks, particles{.style = CrackStyle::particles},
      field{.field = NodeField::sigma_zz}, faults{.faults = true};
  run_cases(made_up_snapshot(2, 140.0),
            {{"cracks", cracks, "png"}, {"particles", particles, "png"}, {"sigma_zz", field, "png"},
             {"faults", faults, "png"}, {"cracks", cracks, "svg"}, {"cracks", cracks, "pdf"}},
            dir);

  run_cases(made_up_snapshot(2, 140.0, true),
            {{"cracks", cracks, "png"}, {"particles", particles, "png"}, {"cracks", cracks, "svg"}},
            dir);

  PictureOptions oblique{.view = PictureView::oblique}, oblique_faults = oblique,
      map{.view = PictureView::map, .field = NodeField::uz};
  oblique_faults.faults = true;
  run_cases(made_up_snapshot(3, 800.0),
            {{"oblique", oblique, "png"}, {"oblique-faults", oblique_faults, "png"},
             {"section", cracks, "png"}, {"map-uz", map, "png"}, {"oblique", oblique, "svg"}},
            dir);
  if (!keep) fs::remove_all(dir);
  return 0;
}
