// latfrac: the command line. run, check, study, analyze, render (docs/cli.md).
//
// Exit status: 0 success, 2 bad input (problem file or option), 3 a run stopped by SIGINT
// or SIGTERM (its results so far and a checkpoint written, docs/restart.md), 1 anything
// else.
#include <latfrac_version.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <new>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "latfrac/analysis/fault_analysis.h"
#include "latfrac/base/error.h"
#include "latfrac/base/parallel.h"
#include "latfrac/base/stop_signal.h"
#include "latfrac/base/threads.h"
#include "latfrac/io/problem_file.h"
#include "latfrac/io/result_file.h"
#include "latfrac/io/result_writer.h"
#include "latfrac/io/xdmf.h"
#include "latfrac/render/render.h"
#include "latfrac/scene/model_builder.h"
#include "latfrac/scene/run.h"
#include "latfrac/scene/size_estimate.h"
#include "latfrac/solvers/linear_backend.h"
#include "latfrac/study/study.h"

namespace fs = std::filesystem;
using namespace latfrac;

namespace {

std::string flown_warning(const RunResult& result);

std::string joined(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) {
    if (i) line += ' ';
    line += argv[i];
  }
  return line;
}

// Refuses a problem whose estimated memory exceeds what the machine has available. With
// the petsc backend: what this machine's ranks need (Open MPI says how many run here).
void check_memory(const Scene& scene, bool force) {
  if (force) return;
  SizeEstimate estimate = estimate_size(scene);
  if (scene.solver.backend == LinearBackendKind::petsc) {
    const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
    const int here = local ? std::max(1, std::atoi(local)) : 1;
    estimate.memory_bytes = here * rank_memory_bytes(estimate, parallel::size());
  }
  const std::string refusal = memory_refusal(scene, estimate, available_memory_bytes());
  if (!refusal.empty()) throw InputError(refusal);
}

// The exit status of a run stopped on request (docs/restart.md).
constexpr int stopped_status = 3;

// An error's message and exit status. Under MPI one rank's error must not leave the others
// waiting in a collective call: it names its rank and stops them all.
int failed(const std::exception& e, int status) {
  if (parallel::distributed()) {
    std::cerr << "latfrac: error (rank " << parallel::rank() << " of " << parallel::size()
              << "): " << e.what() << "\n";
    std::cerr.flush();
    parallel::abort_all(status);
  }
  std::cerr << "latfrac: error: " << e.what() << "\n";
  return status;
}

// What `run` was asked for: a problem to start, or a result file to continue.
struct RunRequest {
  std::string problem;
  std::vector<std::string> sets;
  std::string out_dir, resume;
  double checkpoint_minutes = 1;
  bool quiet = false, force = false;
  std::string command_line;
};

// What even --force cannot change on a resume: what the checkpoint's state counts in
// (the fixed steps of its increment, the loading's direction), the loading already done,
// and the snapshots already taken. Changing these once gave a "complete" file that had
// skipped the steps between (increment 1e-3 -> 1e-2), or an unsigned counter that ran
// below zero (a total below the checkpoint's lambda). The recorded problem is compared
// when this latfrac can still read it.
void check_resumable(const Scene& scene, const std::string& resume, const std::string& problem,
                     const RunCheckpoint& checkpoint) {
  Scene before;
  try {
    before = parse_problem(problem, resume + " /provenance problem", checkpoint.overrides);
  } catch (const InputError&) {
    return;  // another version's problem file: nothing to compare against
  }
  const auto format_number = [](double value) {
    std::ostringstream text;
    text << value;
    return text.str();
  };
  const auto refuse = [&](const std::string& what, const std::string& allowed) {
    throw InputError("cannot resume '" + resume + "', even with --force: " + what +
                     "; allowed: " + allowed);
  };
  const Stepping& now = scene.stepping;
  const Stepping& then = before.stepping;
  if (now.method != then.method ||
      (now.method == SteppingMethod::fixed && now.increment != then.increment))
    refuse(
        "the stepping (method or increment) differs from the one the run started with, "
        "whose steps the checkpoint counts",
        "the stepping the run started with");
  const double reached = checkpoint.lambda;
  const double sense = before.loading.total < 0 ? -1.0 : 1.0;
  if (!(sense * scene.loading.total >= sense * reached))
    refuse("loading.total = " + format_number(scene.loading.total) +
               " is not beyond the lambda the run has reached, " + format_number(reached),
           "a loading.total at or beyond " + format_number(reached) +
               " in the direction the run loads");
  const auto passed = [&](const std::vector<double>& snapshots) {
    std::vector<double> taken;
    for (const double lambda : snapshots)
      if (sense * lambda <= sense * reached) taken.push_back(lambda);
    return taken;
  };
  if (passed(scene.output.snapshots) != passed(before.output.snapshots))
    refuse("output.snapshots changes snapshots at or before the lambda the run has reached, " +
               format_number(reached) + ", which cannot be taken again",
           "the same snapshots up to that lambda; later ones may change");
}

// A resume: the checkpoint and results so far, and the problem they belong to. The
// problem is the file given, or else the file the run started from (or its recorded text
// when that file is gone); a problem or --set list that differs from the recorded one, or
// another latfrac version, is refused unless --force.
Scene resumed_scene(const RunRequest& request, ResumePoint& point) {
  point.checkpoint = read_checkpoint(request.resume);
  point.result = read_result_file(request.resume);
  const Provenance& recorded = point.result.provenance;
  const RunCheckpoint& checkpoint = point.checkpoint;
  const std::string path = request.problem.empty() ? checkpoint.problem_path : request.problem;
  std::error_code missing;
  const bool readable = !path.empty() && fs::is_regular_file(path, missing);
  const std::string text = readable ? read_problem_text(path) : recorded.problem;
  const std::vector<std::string>& sets = request.sets.empty() ? checkpoint.overrides : request.sets;
  if (!request.force) {
    const std::string advice = "; pass --force to resume anyway";
    if (text != recorded.problem) {
      throw InputError("cannot resume '" + request.resume + "': the problem file '" + path +
                       "' differs from the problem the run started with (recorded in the result "
                       "file's /provenance problem)" +
                       advice);
    }
    if (sets != checkpoint.overrides) {
      std::string list;
      for (const std::string& set : checkpoint.overrides)
        list += (list.empty() ? "--set " : " --set ") + set;
      throw InputError("cannot resume '" + request.resume +
                       "': the --set overrides differ from "
                       "those the run started with (" +
                       (list.empty() ? "none" : list) + ")" + advice);
    }
    if (recorded.version != code_version() || recorded.git_commit != code_commit()) {
      throw InputError("cannot resume '" + request.resume + "': it was written by latfrac " +
                       recorded.version + " (commit " + recorded.git_commit + "), this is " +
                       code_version() + " (commit " + code_commit() + ")" + advice);
    }
  }
  Scene scene = parse_problem(text, path.empty() ? request.resume : path, sets);
  if (request.force) check_resumable(scene, request.resume, recorded.problem, checkpoint);
  return scene;
}

int run_command(const RunRequest& request) {
  // 1. Read and validate the scene (or the run to continue); refuse what cannot fit. A
  //    SIGINT or SIGTERM from here on stops the run at its first chance.
  install_stop_handlers();
  if (request.problem.empty() && request.resume.empty())
    throw InputError("run: a problem file is required (or --resume RESULT.h5)");
  if (!request.resume.empty() && !request.out_dir.empty())
    throw InputError("run: --resume continues in the result file's directory; leave out -o");
  if (!(request.checkpoint_minutes >= 0)) {  // negative, or nan (which compares false)
    std::ostringstream value;
    value << request.checkpoint_minutes;
    throw InputError("--checkpoint-every: " + value.str() + " is " +
                     (std::isnan(request.checkpoint_minutes) ? "not a number" : "negative") +
                     "; allowed: minutes >= 0 (0: only when stopping)");
  }
  ResumePoint point;
  const bool resuming = !request.resume.empty();
  const Scene scene =
      resuming ? resumed_scene(request, point) : read_problem_file(request.problem, request.sets);
  // The petsc backend starts MPI here: under mpirun every rank runs the same scene, and
  // rank 0 alone prints and writes (docs/parallel.md).
  start_linear_backend(scene.solver);
  const bool writes = parallel::rank() == 0;
  const bool quiet = request.quiet || !writes;
  check_memory(scene, request.force);
  if (!quiet) std::cout << describe(scene) << "\n";

  // 2. The result file is written from the start, at every checkpoint and at the end;
  //    each write replaces it whole (docs/restart.md).
  std::string h5;
  if (resuming) {
    h5 = request.resume;
  } else {
    const std::string out_dir =
        request.out_dir.empty() ? (fs::path("out") / scene.name).string() : request.out_dir;
    h5 = (fs::path(out_dir) / scene.name).string() + ".h5";
  }
  const std::string base = (fs::path(h5).parent_path() / fs::path(h5).stem()).string();
  const std::string xmf = base + ".xmf";
  std::optional<ResultWriter> writer;
  if (writes) {
    writer.emplace(
        h5, xmf, request.checkpoint_minutes,
        resuming ? point.checkpoint.problem_path : scene.source_path,
        resuming ? (request.sets.empty() ? point.checkpoint.overrides : request.sets) : request.sets,
        resuming && point.checkpoint.started ? point.result.summary.wall_seconds : 0);
  }
  RankedControl control(writer ? &*writer : nullptr);

  // 3. Run it.
  RunOptions options;
  options.command_line = request.command_line;
  options.progress = !quiet;
  options.control = &control;
  if (resuming) {
    options.resume = &point;
    if (!quiet)
      std::cout << "resuming " << h5 << " from lambda " << point.checkpoint.lambda << " ("
                << point.result.events.size() << " events)\n";
  }
  RunResult result;
  try {
    result = run_scene(scene, options);
  } catch (const StopWithinEvent& stop) {
    if (writes)
      std::cerr << "latfrac: " << stop.what() << "; " << h5
                << " holds the last checkpoint written before it\n  continue with: latfrac run "
                   "--resume "
                << h5 << "\n";
    return stopped_status;
  }
  if (!writes) return result.summary.complete ? 0 : stopped_status;
  if (!result.summary.complete) {
    std::cerr << "latfrac: stopped at lambda " << result.summary.final_lambda << " after "
              << result.summary.breaks << " breaks; the results so far and a checkpoint are in "
              << h5 << "\n  continue with: latfrac run --resume " << h5 << "\n";
    return stopped_status;
  }

  // 4. The complete result, its ParaView description and the picture.
  writer->finish(result);
  const std::string picture = base + "." + scene.output.picture_format;
  const std::string flown = flown_warning(result);
  if (!flown.empty()) std::cerr << "latfrac: warning: " << flown << "\n";
  if (scene.output.picture) {
    const PictureReport report =
        render_picture(result, result.snapshots.size() - 1, picture, scene.output.picture_options);
    if (!report.note.empty() && flown.empty()) std::cerr << "latfrac: note: " << report.note << "\n";
  }

  // 5. The summary.
  if (!quiet) {
    std::cout << summary_text(result) << "  wrote " << h5 << ", " << xmf
              << (scene.output.picture ? ", " + picture : "") << "\n  wrote the result file "
              << writer->writes() << " times, in " << writer->write_seconds() << " s\n";
  }
  return 0;
}

int check_command(const std::string& problem, const std::vector<std::string>& sets) {
  const Scene scene = read_problem_file(problem, sets);
  const SizeEstimate estimate = estimate_size(scene);
  // The model's own checks (weights and failure strains that overflow, a layer's
  // density, friction without shear springs) come when it is built: check builds it when
  // that is quick, so that check and run refuse the same problems.
  constexpr double most_nodes_to_build = 300000;
  if (estimate.nodes <= most_nodes_to_build) {
    try {
      build_model(scene);
    } catch (const InputError& e) {
      throw InputError(problem + ": " + e.what());
    }
  }
  std::cout << describe(scene) << "\n" << describe(estimate);
  if (estimate.nodes > most_nodes_to_build)
    std::cout << "note: the model's own checks (weights and strengths that overflow, friction "
                 "without shear springs) run when latfrac run builds it (more than "
              << most_nodes_to_build << " nodes: not built here)\n";
  const double available = available_memory_bytes();
  if (available > 0) std::cout << "  available memory " << readable_bytes(available) << "\n";
  if (scene.solver.backend == LinearBackendKind::petsc) std::cout << describe_ranks(estimate, available);
  // With the petsc backend the memory needed depends on the ranks: describe_ranks says it.
  if (const std::string refusal = memory_refusal(scene, estimate, available);
      !refusal.empty() && scene.solver.backend == LinearBackendKind::cholmod) {
    std::cout << "note: run will refuse this problem without --force: " << refusal << "\n";
  }
  const auto missing = unsupported_effects(scene);
  for (const std::string& effect : missing) {
    std::cout << "note: this version cannot yet simulate " << effect << "\n";
  }
  bool no_shear = scene.material.poisson == 0.25;
  for (const Layer& layer : scene.layers) no_shear = no_shear || layer.material.poisson == 0.25;
  if (no_shear && scene.strength) {
    std::cout << "note: at poisson = 0.25 the lattice has no shear springs, so breaking leaves "
                 "mechanisms (pieces that turn about a node); the run holds each where it "
                 "appears (docs/robustness.md, \"Mechanisms\"); 0.24 keeps shear springs\n";
  }
  std::cout << "ok: " << problem << " is valid\n";
  return 0;
}

int study_command(const std::string& problem, const std::vector<std::string>& sets,
                  const std::string& increments, std::string out_dir, bool relaxation, bool quiet,
                  bool force, const std::string& command_line) {
  // 1. Check the increments before anything runs; read the scene; refuse what cannot fit.
  StudyOptions options;
  options.increments = parse_increments(increments);
  // The study's runs take their own snapshot at loading.total (study.h), so the file's
  // snapshots are dropped first: a --set loading.total below them is not refused for
  // them. A --set output.snapshots still applies, and is checked as in run.
  std::vector<std::string> study_sets{"output.snapshots=[]"};
  study_sets.insert(study_sets.end(), sets.begin(), sets.end());
  const Scene scene = read_problem_file(problem, study_sets);
  if (scene.solver.backend == LinearBackendKind::petsc)
    throw InputError(problem + ": solver.backend = \"petsc\" is for latfrac run (under mpirun); "
                     "latfrac study runs on the cholmod backend (--set solver.backend=cholmod)");
  check_memory(scene, force);
  if (!quiet) {
    std::cout << describe(scene) << "\nstudy: the event-driven reference, then fixed-step at ds =";
    for (double ds : options.increments) std::cout << " " << increment_text(ds);
    std::cout << (relaxation ? " (each also with relaxation)" : "") << "\n";
  }

  // 2. The reference (event-driven), then a fixed-step run per increment; a line per run.
  options.relaxation = relaxation;
  options.command_line = command_line;
  options.run_progress = !quiet;
  if (!quiet) options.on_row = [](const StudyRow& row) { std::cerr << progress_line(row) << "\n"; };
  install_stop_handlers();  // SIGINT, SIGTERM: the study stops between a run's events
  const StudyResult study = run_study(scene, options);
  if (study.stopped) {
    std::cerr << "latfrac: study stopped on request after " << study.rows.size() << " of "
              << 1 + options.increments.size() * (relaxation ? 2 : 1)
              << " runs; no study files were written (a study is written whole)\n";
    return stopped_status;
  }

  // 3. study.csv, study.md and study.png, each complete or absent.
  if (out_dir.empty()) out_dir = (fs::path("out") / scene.name / "study").string();
  write_study(study, out_dir);
  if (!quiet) {
    for (const std::string& line : study_interpretation(study))
      if (!line.empty()) std::cout << line << "\n";
    std::cout << "wrote " << (fs::path(out_dir) / "study.csv").string()
              << ", study.md, study.png\n";
  }
  return 0;
}

// The snapshot nearest the requested lambda (the last when none was requested). When the
// nearest is not at the requested lambda, says so on stderr (stdout may be JSON), with the
// lambdas the result holds: a silent substitution would be read as the requested state.
std::size_t chosen_snapshot(const RunResult& result, double lambda) {
  const std::size_t index = snapshot_nearest(result, lambda);
  const double found = result.snapshots[index].lambda;
  if (std::isnan(lambda) || std::abs(found - lambda) <= 1e-9 * std::max(1e-12, std::abs(lambda)))
    return index;
  std::ostringstream held;
  for (std::size_t k = 0; k < result.snapshots.size(); ++k)
    held << (k ? ", " : "") << result.snapshots[k].lambda;
  std::cerr << "latfrac: no snapshot at lambda " << lambda << "; using the nearest, lambda "
            << found << " (the result holds " << held.str()
            << "; more with output.snapshots in the problem file)\n";
  return index;
}

int analyze_command(const std::string& path, bool json, double lambda, double min_offset) {
  if (!(min_offset >= 0) || !std::isfinite(min_offset))
    throw InputError("--min-offset must be 0 or more (m) and finite");
  // 1. Read the result; 2. analyse the faults of the chosen snapshot; 3. print.
  const RunResult result = read_result_file(path);
  // A result without snapshots (a run stopped before its first) has no faults to analyse:
  // "faults" is null in JSON.
  const bool none = result.snapshots.empty();
  if (none && !json) {
    std::cout << summary_text(result) << "fault analysis: the result holds no snapshot\n";
    return 0;
  }
  std::optional<FaultReport> report;
  FaultOptions options;
  options.min_offset = min_offset;
  if (!none) report = analyze_faults(result, chosen_snapshot(result, lambda), options);
  if (json) {
    const std::string faults = report ? to_json(*report) : "null";
    const RunSummary& s = result.summary;
    std::printf(
        "{\"name\": \"%s\", \"model\": \"%s\", \"complete\": %s, \"dim\": %d, \"nodes\": %zu, "
        "\"bonds\": %zu, \"breaks\": %lld, "
        "\"final_lambda\": %.17g, \"wall_seconds\": %.6g, \"solves\": %lld, \"factorizations\": "
        "%lld, "
        "\"factor_updates\": %lld, \"snapshots\": %zu, \"faults\": %s}\n",
        result.scene.name.c_str(), result.scene.model.c_str(), s.complete ? "true" : "false",
        result.scene.dim, result.node_count(), result.bond_count(),
        static_cast<long long>(s.breaks), s.final_lambda, s.wall_seconds,
        static_cast<long long>(s.solves), static_cast<long long>(s.factorizations),
        static_cast<long long>(s.factor_updates), result.snapshots.size(), faults.c_str());
    return 0;
  }
  std::cout << summary_text(result) << "\n" << to_text(*report);
  return 0;
}

// The render options given by name on the command line.
struct RenderNames {
  std::string view = "section", style = "cracks", field = "none";
  std::optional<double> section_y, section_x;
};

template <class Enum>
Enum named_option(std::optional<Enum> (*lookup)(std::string_view), const std::string& option,
                  const std::string& name, const std::vector<std::string_view>& names) {
  if (const std::optional<Enum> value = lookup(name)) return *value;
  throw InputError(option + " \"" + name + "\" is not known; allowed: " + list_of_names(names));
}

PictureOptions picture_options(const RenderNames& names, int width, double exaggeration,
                               bool faults, double min_offset) {
  PictureOptions options;
  options.min_offset = min_offset;
  options.view = named_option(picture_view_named, "--view", names.view, picture_view_names());
  options.style = named_option(crack_style_named, "--style", names.style, crack_style_names());
  options.field = named_option(node_field_named, "--field", names.field, node_field_names());
  options.faults = faults;
  options.width = width;
  options.exaggeration = exaggeration;
  if (names.section_y && names.section_x)
    throw InputError("--section-y and --section-x: give one of the two");
  if (names.section_x) options.section_axis = SectionAxis::x;
  options.section_at = names.section_x ? names.section_x : names.section_y;
  return options;
}

// A node that moved farther than the lattice's size has left small-strain mechanics: a
// piece that found no equilibrium (docs/robustness.md, "Mechanisms": pieces on
// frictionless contacts under gravity), or a material too soft for its load. The first
// snapshot where that happens, or "".
std::string flown_warning(const RunResult& result) {
  // The body's smallest extent, not its largest: a 5 km slab compressed to -0.5 rose
  // 29.5 km, within its 60 km length, without a word.
  const double size = result.smallest_extent();
  for (const Snapshot& snapshot : result.snapshots) {
    double largest = 0;
    for (const double u : snapshot.displacement) largest = std::max(largest, std::abs(u));
    if (!(largest > size)) continue;
    std::ostringstream text;
    text << std::setprecision(3) << "by lambda " << snapshot.lambda << " nodes moved by up to "
         << largest << " m, more than the lattice's smallest extent (" << size
         << " m): small-strain mechanics does not hold there, and the results from there on "
            "are not physical (a piece that found no equilibrium, as pieces on frictionless "
            "contacts under gravity can, a material too soft for its load, or a loading far "
            "beyond small strain; "
            "docs/robustness.md, \"Mechanisms\")";
    return text.str();
  }
  return "";
}

int render_command(const std::string& path, double lambda, const std::string& picture,
                   const PictureOptions& options) {
  picture_format_of(picture);  // an unsupported extension is refused before reading
  const RunResult result = read_result_file(path);
  const std::size_t index = chosen_snapshot(result, lambda);
  const PictureReport report = render_picture(result, index, picture, options);
  if (!report.note.empty()) std::cerr << "latfrac: note: " << report.note << "\n";
  std::cout << "wrote " << picture << " (lambda " << result.snapshots[index].lambda << ")\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"latfrac: brittle fracture in lattice models of the crust"};
  app.require_subcommand(0, 1);
  bool version = false;
  app.add_flag("--version", version, "print the version and the commit it was built from");

  std::string problem, result_path, out_dir, png;
  std::vector<std::string> sets;
  bool quiet = false, force = false, json = false;
  double lambda = std::numeric_limits<double>::quiet_NaN(), exaggeration = -1;
  int width = 1600;

  RunRequest request;
  auto* run = app.add_subcommand("run", "run a problem file and write its results");
  run->add_option("problem", problem, "the problem file (TOML)")->check(CLI::ExistingFile);
  // An empty -o "" would fall back to the default silently: refused.
  const CLI::Validator directory(
      [](std::string& v) { return v.empty() ? "an empty directory name" : ""; }, "DIR",
      "non-empty");
  run->add_option("-o,--output", out_dir, "output directory (default out/<name>/)")
      ->check(directory);
  run->add_option("--set", sets, "override a key: --set lattice.spacing=500");
  run->add_flag("--quiet", quiet, "print nothing but errors");
  run->add_flag("--force", force,
                "run even when the memory estimate exceeds the available memory; resume "
                "despite a changed problem or another latfrac version");
  run->add_option("--resume", request.resume,
                  "continue the stopped run whose incomplete result file this is")
      ->check(CLI::ExistingFile);
  run->add_option("--checkpoint-every", request.checkpoint_minutes,
                  "minutes between checkpoints (default 1; 0: only when stopping)");

  auto* check =
      app.add_subcommand("check", "validate a problem file and estimate its size; write nothing");
  check->add_option("problem", problem, "the problem file (TOML)")
      ->required()
      ->check(CLI::ExistingFile);
  check->add_option("--set", sets, "override a key: --set lattice.spacing=500");

  std::string increments;
  bool relaxation = false;
  auto* study = app.add_subcommand(
      "study", "convergence study: fixed-step runs against the event-driven reference");
  study->add_option("problem", problem, "the problem file (TOML)")
      ->required()
      ->check(CLI::ExistingFile);
  study
      ->add_option("--increments", increments,
                   "fixed-step increments ds, comma-separated: 1e-2,3e-3,1e-3")
      ->required();
  study->add_option("-o,--output", out_dir, "output directory (default out/<name>/study/)")
      ->check(directory);
  study->add_option("--set", sets, "override a key: --set lattice.spacing=500");
  study->add_flag("--relaxation", relaxation,
                  "also run each increment with solver.method = relaxation");
  study->add_flag("--quiet", quiet, "print nothing but errors");
  study->add_flag("--force", force,
                  "run even when the memory estimate exceeds the available memory");

  double min_offset = 0;  // m (analyze and render --min-offset)
  auto* analyze = app.add_subcommand("analyze", "summarise a result file");
  analyze->add_option("result", result_path, "a result file (.h5)")
      ->required()
      ->check(CLI::ExistingFile);
  analyze->add_flag("--json", json, "machine-readable output");
  analyze->add_option("--lambda", lambda, "the snapshot nearest this lambda (default: the last)");
  analyze->add_option("--min-offset", min_offset,
                      "analyse only the broken bonds whose nodes moved apart by at least this "
                      "much, m (default 0: all)");

  RenderNames names;
  bool faults = false;
  auto* render = app.add_subcommand("render", "draw a snapshot as a PNG, SVG or PDF picture");
  render->add_option("result", result_path, "a result file (.h5)")
      ->required()
      ->check(CLI::ExistingFile);
  render->add_option("--lambda", lambda, "the snapshot nearest this lambda (default: the last)");
  render->add_option("-o,--output", png, "the picture to write: FILE.png, FILE.svg or FILE.pdf")
      ->required();
  render->add_option("--width", width, "picture width in pixels")->check(CLI::Range(200, 20000));
  render
      ->add_option("--exaggeration", exaggeration,
                   "displacement magnification (default: the scene's)")
      ->check(CLI::Range(0.0, max_exaggeration));
  render->add_option("--view", names.view, "section, map (3-D) or oblique (3-D); default section");
  render->add_option("--style", names.style,
                     "cracks (broken bonds coloured by mode) or particles (the paper's red "
                     "particles); default cracks");
  render->add_option("--field", names.field,
                     "colour the nodes by: " + list_of_names(node_field_names()));
  render->add_flag("--faults", faults, "draw the fitted faults (alpha, dip) and grabens");
  render->add_option("--min-offset", min_offset,
                     "draw (and with --faults analyse) only the broken bonds whose nodes moved "
                     "apart by at least this much, m (default 0: all)");
  render->add_option("--section-y", names.section_y, "3-D: the section at this y, m");
  render->add_option("--section-x", names.section_x, "3-D: the section at this x, m");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int status = app.exit(e);
    return status == 0 ? 0 : 2;
  }
  try {
    if (version) {
      std::cout << "latfrac " << LATFRAC_VERSION << " (commit " << LATFRAC_GIT_COMMIT << ")\n";
      return 0;
    }
    // A bad LATFRAC_THREADS is refused before anything is read or written.
    if (*run || *check || *study) threads::count();
    if (*run) {
      request.problem = problem;
      request.sets = sets;
      request.out_dir = out_dir;
      request.quiet = quiet;
      request.force = force;
      request.command_line = joined(argc, argv);
      return run_command(request);
    }
    if (*check) return check_command(problem, sets);
    if (*study)
      return study_command(problem, sets, increments, out_dir, relaxation, quiet, force,
                           joined(argc, argv));
    // NaN stands for "not given" inside; a given --lambda must be a finite loading (inf
    // picked the first snapshot, nan the last, both silently).
    for (const CLI::App* command : {analyze, render})
      if (*command && command->count("--lambda") > 0 && !std::isfinite(lambda))
        throw InputError("--lambda must be a finite number (a loading, strain), got " +
                         command->get_option("--lambda")->as<std::string>());
    if (*analyze) return analyze_command(result_path, json, lambda, min_offset);
    if (*render)
      return render_command(result_path, lambda, png,
                            picture_options(names, width, exaggeration, faults, min_offset));
    std::cout << app.help();
    return 2;
  } catch (const InputError& e) {
    return failed(e, 2);
  } catch (const std::bad_alloc&) {
    // Allocation failed or a size exceeded what a vector can hold: a scene too large for
    // this machine (run refuses those unless --force), or a factor that filled in beyond
    // memory. std::bad_alloc's own text says none of that.
    return failed(std::runtime_error("out of memory: latfrac needed more memory than this "
                                     "machine could give (`latfrac check` estimates a run's "
                                     "needs; a larger lattice.spacing needs less)"),
                  1);
  } catch (const std::length_error& e) {
    return failed(std::runtime_error(std::string("out of memory: an array would exceed what "
                                                 "memory can hold (") +
                                     e.what() + "); a larger lattice.spacing needs less"),
                  1);
  } catch (const std::exception& e) {
    return failed(e, 1);
  }
}
