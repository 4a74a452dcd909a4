// The run: build the model, follow the equilibrium path in lambda, record snapshots.
#include "latfrac/scene/run.h"

#include <latfrac_version.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <iomanip>
#include <optional>
#include <sstream>

#include "latfrac/base/error.h"
#include "latfrac/base/number_text.h"
#include "latfrac/base/phase_times.h"
#include "latfrac/base/progress.h"
#include "latfrac/fracture/fracture_run.h"
#include "latfrac/fracture/initial_supports.h"
#include "latfrac/fracture/schedule.h"
#include "latfrac/fracture/snapshots.h"
#include "latfrac/scene/model_builder.h"
#include "latfrac/solvers/equilibrium.h"

namespace latfrac {

std::string utc_timestamp() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

std::string code_version() { return LATFRAC_VERSION; }
std::string code_commit() { return LATFRAC_GIT_COMMIT; }

namespace {

Provenance provenance_of(const Scene& scene, const RunOptions& options) {
  Provenance p;
  p.version = code_version();
  p.git_commit = code_commit();
  p.command_line = options.command_line;
  p.problem = scene.source_text;
  p.created = utc_timestamp();
  p.seed = scene.heterogeneity ? scene.heterogeneity->seed : 0;
  return p;
}

// A linear elastic scene follows an affine path: one factorization and one two-column
// solve give every lambda; KINSOL then confirms equilibrium at each snapshot. A nonlinear
// one (large kinematics) is solved by KINSOL snapshot after snapshot, each from the one
// before.
void run_elastic(const Scene& scene, const Model& model, EquilibriumSolver& solver,
                 ProgressLine& progress, RunResult& result) {
  const bool linear = model.is_linear();
  const AffinePath path = linear ? solver.affine_path() : AffinePath{};
  std::vector<double> lambdas = scene.output.snapshots;
  if (lambdas.empty()) lambdas.push_back(scene.loading.total);
  Vector free_displacement = Vector::Zero(model.dofs().free_count);
  for (double lambda : lambdas) {
    if (linear) free_displacement = path.at(lambda);
    solver.solve(lambda, free_displacement);
    result.snapshots.push_back(
        make_snapshot(model, model.full_displacement(free_displacement, lambda), lambda, nullptr));
    progress.update(lambda, 0);
  }
}

// Puts the model into the checkpoint's pair states and supports (before a solver exists).
void restore_model(Model& model, const RunCheckpoint& checkpoint, const std::string& source) {
  const auto bonds = static_cast<std::size_t>(model.lattice.bond_count());
  const auto dofs = static_cast<std::size_t>(model.dofs().dof_count());
  if (checkpoint.pair_states.size() != bonds || checkpoint.free_index.size() != dofs ||
      checkpoint.prescribed_base.size() != dofs || checkpoint.prescribed_rate.size() != dofs) {
    throw InputError(source + ": the checkpoint does not fit this problem's model (it has " +
                     std::to_string(checkpoint.pair_states.size()) + " bonds and " +
                     std::to_string(checkpoint.free_index.size()) + " degrees of freedom, the " +
                     "problem " + std::to_string(bonds) + " and " + std::to_string(dofs) + ")");
  }
  // The pair states of the last factorization: the solver replays the changes since.
  const EquilibriumSolver::History& factor = checkpoint.factor;
  if (factor.factor_current && factor.factored_states.size() != bonds)
    throw InputError(source +
                     ": the checkpoint's factor history does not fit this problem's model");
  const std::vector<std::uint8_t>& states =
      factor.factor_current ? factor.factored_states : checkpoint.pair_states;
  ModelEditor editor(model);
  for (std::size_t b = 0; b < bonds; ++b)
    editor.set_state(static_cast<std::int64_t>(b), static_cast<PairState>(states[b]));
  const std::size_t values = RunCheckpoint::memory_values;
  if (model.has_friction() != !checkpoint.contact_memory.empty() ||
      (model.has_friction() && checkpoint.contact_memory.size() != bonds * values))
    throw InputError(source + ": the checkpoint's contact memory does not fit this problem's " +
                     "friction");
  for (std::size_t b = 0; b < bonds && model.has_friction(); ++b) {
    const double* v = &checkpoint.contact_memory[b * values];
    editor.set_memory(static_cast<std::int64_t>(b),
                      {Vec3(v[0], v[1], v[2]), Vec3(v[3], v[4], v[5]), v[6], v[7], v[8]});
  }
  // Contacts along cracks: the normals the run's breaks chose (a pre-cut's come from the
  // problem; the checkpoint has them too).
  if (model.contacts_along_cracks() != !checkpoint.contact_normals.empty() ||
      (model.contacts_along_cracks() && checkpoint.contact_normals.size() != bonds * 3))
    throw InputError(source + ": the checkpoint's contact normals do not fit this problem's " +
                     "contact.normal");
  for (std::size_t b = 0; b < bonds && model.contacts_along_cracks(); ++b) {
    const double* v = &checkpoint.contact_normals[b * 3];
    const Vec3 n(v[0], v[1], v[2]);
    if (!(std::abs(n.norm() - 1) < 1e-9))
      throw InputError(source + ": the checkpoint's contact normal of bond " + std::to_string(b) +
                       " is not a unit vector (the result file is damaged or was edited)");
    model.contact_normal[b] = n;
  }
  DofMap map;
  map.dim = model.dim();
  map.free_index = checkpoint.free_index;
  map.prescribed_base = checkpoint.prescribed_base;
  map.prescribed_rate = checkpoint.prescribed_rate;
  for (std::int64_t index : map.free_index) map.free_count += index >= 0 ? 1 : 0;
  editor.set_dofs(std::move(map));
}

// The checkpoint against the rest of its file and the problem: where the run stood
// (lambda, step, snapshots taken, parts held) must be a place this problem's run can
// stand. Otherwise the resumed run would index out of range, or write a file that says
// complete without what it lacks. (The events' bonds were checked on reading the file,
// read_result_file; the checkpoint's own indices by read_checkpoint.)
void check_resume_point(const ResumePoint& resume, const Schedule& schedule,
                        const std::string& source) {
  const RunCheckpoint& c = resume.checkpoint;
  auto refuse = [&](const std::string& what) {
    throw InputError(source + ": cannot resume: the checkpoint " + what +
                     " (the result file is damaged or was edited)");
  };
  const auto taken = static_cast<std::int64_t>(resume.result.snapshots.size());
  const auto planned =
      static_cast<std::int64_t>(std::max<std::size_t>(1, schedule.snapshots.size()));
  if (c.snapshots_taken != taken || c.snapshots_taken > planned)
    refuse("says " + std::to_string(c.snapshots_taken) + " snapshots were taken; the file holds " +
           std::to_string(taken) + " of the " + std::to_string(planned) + " planned");
  if (c.fragments_at_start > static_cast<std::int64_t>(resume.result.fragments.size()))
    refuse("names more parts held at the start than the file holds");
  const double sign = schedule.total < 0 ? -1.0 : 1.0;
  if (sign * c.lambda < 0 || sign * c.lambda > std::abs(schedule.total))
    refuse("stands at lambda " + std::to_string(c.lambda) + ", outside the loading 0 .. " +
           std::to_string(schedule.total));
  if (schedule.stepping.method == SteppingMethod::fixed) {
    const long steps = fixed_step_count(schedule.total, schedule.stepping.increment);
    if (c.next_step > steps)
      refuse("stands at step " + std::to_string(c.next_step) + " of " + std::to_string(steps));
  }
}

}  // namespace

std::vector<std::string> unsupported_effects(const Scene& scene) {
  std::vector<std::string> missing;
  if (scene.contact && !scene.strength) {
    missing.push_back(
        "[contact] on an elastic scene (contacts are settled by the fracture run: add a "
        "[strength] section, with a strength that cannot be reached if nothing should break)");
  }
  if (scene.contact && scene.contact->friction > 0) {
    if (scene.large_kinematics)
      missing.push_back("contact.friction with large_kinematics (friction needs affine paths)");
    if (scene.solver.method == EquilibriumMethod::relaxation)
      missing.push_back("contact.friction with solver.method = \"relaxation\"");
  }
  if (scene.solver.method == EquilibriumMethod::relaxation && !scene.strength) {
    missing.push_back(
        "solver.method = \"relaxation\" on an elastic scene (it is the fracture baseline)");
  }
  return missing;
}

void check_step_count(double total, double increment, const std::string& what) {
  const double steps = std::abs(total) / increment;
  if (steps <= max_fixed_steps) return;
  std::ostringstream message;
  message << what << " = " << increment << " makes " << steps << " fixed steps to loading.total = "
          << total << "; allowed: at most 1e9 steps (an increment of at least "
          << std::abs(total) / max_fixed_steps << ")";
  throw InputError(message.str());
}

RunResult run_scene(const Scene& scene, const RunOptions& options) {
  if (const auto missing = unsupported_effects(scene); !missing.empty()) {
    std::string list;
    for (const std::string& effect : missing) list += (list.empty() ? "" : ", ") + effect;
    throw InputError(scene.source_path + ": this version of latfrac cannot yet simulate " + list);
  }
  if (scene.strength && scene.solver.method == EquilibriumMethod::relaxation &&
      scene.stepping.method == SteppingMethod::event) {
    throw InputError(
        scene.source_path +
        ": solver.method = \"relaxation\" works with the fixed-step "
        "method only (stepping.method = \"fixed\"): events need the exact affine path");
  }
  if (scene.stepping.method == SteppingMethod::fixed)
    check_step_count(scene.loading.total, scene.stepping.increment,
                     (scene.source_path.empty() ? "" : scene.source_path + ": ") + "stepping.increment");
  const auto start = std::chrono::steady_clock::now();
  phase_clock().reset();
  std::optional<ScopedPhase> setup(std::in_place, Phase::setup);
  // A checkpoint written before the run began is continued by starting afresh.
  const ResumePoint* resume =
      options.resume && options.resume->checkpoint.started ? options.resume : nullptr;
  RunResult result;
  result.provenance = provenance_of(scene, options);
  result.scene = {scene.name, scene.lattice.dim, scene.lattice.spacing, "",
                  scene.output.exaggeration, model_label(scene)};

  // One criterion object, resolved once, gives the model its strengths and the run its f.
  const std::shared_ptr<const FailureCriterion> criterion =
      scene.strength ? make_criterion(*scene.strength, scene.lattice.dim) : nullptr;
  if (criterion) result.scene.criterion = to_string(scene.strength->criterion);
  // The model's own checks (scales, initial stress) name keys, not lines: say the file.
  Model model = [&] {
    try {
      return build_model(scene, criterion.get());
    } catch (const InputError& e) {
      if (scene.source_path.empty()) throw;
      throw InputError(scene.source_path + ": " + e.what());
    }
  }();
  record_lattice(model, result);
  result.fragments = prepare_supports(model, scene.source_path);
  double wall_before = 0;
  if (resume) {
    if (resume->result.positions != result.positions || resume->result.bonds != result.bonds)
      throw InputError(scene.source_path + ": the result file's lattice is not this problem's");
    restore_model(model, resume->checkpoint, scene.source_path);
    check_resume_point(*resume, schedule_of(scene), scene.source_path);
    result.provenance = resume->result.provenance;
    result.events = resume->result.events;
    result.snapshots = resume->result.snapshots;
    result.fragments = resume->result.fragments;
    wall_before = resume->result.summary.wall_seconds;
  } else if (options.control) {
    // The file exists from the start: lattice and provenance, nothing run yet.
    RunCheckpoint not_started;
    result.summary.complete = false;
    options.control->save(result, not_started);
    result.summary.complete = true;
  }
  EquilibriumSolver solver(model, scene.solver);
  if (resume) {
    std::vector<PairState> states;
    for (std::uint8_t state : resume->checkpoint.pair_states)
      states.push_back(static_cast<PairState>(state));
    solver.rebuild(resume->checkpoint.factor, states);
  }
  ProgressLine progress(options.progress);

  if (criterion) {
    FractureRun fracture(model, criterion, scene.strength->bond_stress, schedule_of(scene),
                         scene.solver, solver, progress, result);
    fracture.set_control(options.control);
    if (resume) fracture.resume_from(resume->checkpoint, resume->result.summary);
    setup.reset();
    try {
      fracture.run();
    } catch (const RunStopped&) {
      if (options.backend_statistics) *options.backend_statistics = solver.factor().statistics();
      progress.finish();
      result.summary.phase_seconds = phase_clock().seconds();
      result.summary.wall_seconds =
          wall_before +
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return result;  // as saved: summary.complete is false
    }
    static_cast<RunCounters&>(result.summary) = fracture.counters();
  } else {
    setup.reset();
    run_elastic(scene, model, solver, progress, result);
    result.summary.solves = solver.counters().solves;
    result.summary.factorizations = solver.counters().factorizations;
    result.summary.factor_updates = solver.counters().factor_updates;
    result.summary.floor_acceptances = solver.counters().floor_acceptances;
  }
  progress.finish();
  if (options.backend_statistics) *options.backend_statistics = solver.factor().statistics();

  result.summary.final_lambda = scene.loading.total;
  result.summary.complete = true;
  result.summary.phase_seconds = phase_clock().seconds();
  result.summary.wall_seconds =
      wall_before + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

// "  time by part (this process, s): solves 41.2, ..." in Phase order, the parts with
// any time; empty when the split was not measured.
std::string time_split_text(const RunSummary& s) {
  std::ostringstream text;
  text << std::setprecision(3);
  bool any = false;
  for (int p = 1; p <= phase_count; ++p) {
    const int phase = p % phase_count;  // `the rest` last
    if (!(s.phase_seconds[phase] > 0)) continue;
    text << (any ? ", " : "  time by part (this process, s): ")
         << to_string(static_cast<Phase>(phase)) << " " << s.phase_seconds[phase];
    any = true;
  }
  if (any) text << "\n";
  return text.str();
}

std::string summary_text(const RunResult& result) {
  std::ostringstream text;
  const RunSummary& s = result.summary;
  text << "summary of " << result.scene.name << " (" << result.scene.dim << "-D, spacing "
       << result.scene.spacing << " m, "
       << (result.scene.criterion.empty() ? "elastic" : result.scene.criterion) << ")\n"
       << (result.scene.model.empty() ? "" : "  model: " + result.scene.model + "\n") << "  nodes "
       << result.node_count() << ", bonds " << result.bond_count() << "\n"
       << (s.complete ? ""
                      : "  incomplete: written during the run, or the run stopped (latfrac run "
                        "--resume continues it)\n")
       << "  final lambda " << s.final_lambda << ", bonds broken " << s.breaks << ", events "
       << result.events.size() << "\n"
       << "  parts held for lack of support " << result.fragments.size()
       << ", contact cycles resolved " << s.contact_cycles << "\n"
       << (s.relaxation_sweeps ? "  relaxation sweeps " + std::to_string(s.relaxation_sweeps) +
                                     ", solves stopped by the sweep cap " +
                                     std::to_string(s.relaxation_unconverged) + "\n"
                               : std::string())
       << (result.contact_slip.empty()
               ? std::string()
               : "  friction: contact slip " + significant(s.contact_slip, 6) +
                     " m in all, work dissipated " + significant(s.friction_work, 6) +
                     (result.scene.dim == 2 ? " J per metre\n" : " J\n"))
       << "  solves " << s.solves << ", factorizations " << s.factorizations << ", factor updates "
       << s.factor_updates << "\n"
       << (s.floor_acceptances
               ? "  solutions accepted at the rounding floor, above solver.tolerance: " +
                     std::to_string(s.floor_acceptances) + " (docs/robustness.md)\n"
               : std::string())
       << "  wall time " << s.wall_seconds << " s\n"
       << time_split_text(s);
  for (const Snapshot& snapshot : result.snapshots) {
    double max_u = 0, min_zz = 0, max_zz = 0;
    for (std::size_t n = 0; n < result.node_count(); ++n) {
      const double* u = &snapshot.displacement[3 * n];
      max_u = std::max(max_u, std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]));
      min_zz = std::min(min_zz, snapshot.node_stress[6 * n + 2]);
      max_zz = std::max(max_zz, snapshot.node_stress[6 * n + 2]);
    }
    text << "  snapshot lambda " << snapshot.lambda << ": max |u| " << max_u << " m, sigma_zz from "
         << min_zz / 1e6 << " to " << max_zz / 1e6 << " MPa\n";
  }
  text << "  made by latfrac " << result.provenance.version << " (" << result.provenance.git_commit
       << ") on " << result.provenance.created << "\n";
  return text.str();
}

}  // namespace latfrac
