// The numerical question of the distributed backend (issue 20), measured before building
// it: distributed direct solvers have no rank updates, so how should a run solve with the
// stiffness after r breaks? The 3-D reference block (problems/reference-3d.toml, its
// stiffness assembled by latfrac on the free dofs, gravity as the right-hand side) is
// handed to PETSc, its rows split in contiguous blocks across the MPI ranks, and:
//   1. K0 is factorized by MUMPS (Cholesky) and solved: the cost of a factorization;
//   2. r bonds are removed (the r uppermost bonds crossing the mid-plane x = 30 km, a
//      fault growing down from the surface) and K_r x = b is solved by CG preconditioned
//      with K0's MUMPS factor, from zero: the preconditioned operator is the identity
//      plus a term of rank <= 6 r (3-D: two springs per bond, up to 6 dofs), so CG needs
//      about that many iterations at most, and in practice far fewer;
//   3. the same K_r x = b by CG preconditioned with algebraic multigrid (PETSc's GAMG and
//      hypre's BoomerAMG), warm-started from K0's solution, as a run would start from its
//      last state;
//   4. a fresh MUMPS factorization of K_r.
// Every solve is checked: |b - K_r x| / |b| <= 1e-10. Peak resident memory per rank
// (getrusage) is printed at the end.
//
//   build/bench/bench_petsc [spacing m] [r ...]          # default: 2000 m, r = 1 10 100
//   mpirun --allow-run-as-root -np 2 build/bench/bench_petsc 1000 1 10 100 1000
//
// Built only when CMake finds PETSc (pkg-config PETSc: Debian's libpetsc-real-dev).
#include <mpi.h>
#include <petscksp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "latfrac/fracture/initial_supports.h"
#include "latfrac/io/problem_file.h"
#include "latfrac/mechanics/stiffness.h"
#include "latfrac/scene/model_builder.h"

#include "peak_memory.h"

using namespace latfrac;

namespace {

int rank = 0, ranks = 1;

void check(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  std::fprintf(stderr, "bench_petsc: %s failed (PETSc error %d)\n", what, static_cast<int>(code));
  MPI_Abort(MPI_COMM_WORLD, 1);
}

// The full symmetric matrix from latfrac's upper triangle (CSC), as rows.
using Rows = std::vector<std::vector<std::pair<PetscInt, double>>>;

Rows rows_of(StiffnessMatrix& k) {
  Rows rows(static_cast<std::size_t>(k.size()));
  const auto& start = k.column_start();
  const auto& row = k.row_index();
  const auto& value = k.values();
  for (std::int64_t j = 0; j < k.size(); ++j) {
    for (std::int64_t p = start[j]; p < start[j + 1]; ++p) {
      if (value[p] == 0) continue;
      rows[row[p]].push_back({static_cast<PetscInt>(j), value[p]});
      if (row[p] != j) rows[j].push_back({static_cast<PetscInt>(row[p]), value[p]});
    }
  }
  return rows;
}

// An AIJ matrix (sequential on one rank, MPI on more) holding this rank's block of rows.
Mat petsc_matrix(const Rows& rows, PetscInt first, PetscInt last) {
  const auto n = static_cast<PetscInt>(rows.size());
  std::vector<PetscInt> diagonal(last - first), off(last - first);
  for (PetscInt i = first; i < last; ++i)
    for (const auto& [c, v] : rows[i]) ++((c >= first && c < last) ? diagonal : off)[i - first];
  Mat a;
  check(MatCreate(PETSC_COMM_WORLD, &a), "MatCreate");
  check(MatSetSizes(a, last - first, last - first, n, n), "MatSetSizes");
  check(MatSetType(a, MATAIJ), "MatSetType");
  check(MatSeqAIJSetPreallocation(a, 0, diagonal.data()), "preallocation");
  check(MatMPIAIJSetPreallocation(a, 0, diagonal.data(), 0, off.data()), "preallocation");
  std::vector<PetscInt> columns;
  std::vector<double> values;
  for (PetscInt i = first; i < last; ++i) {
    columns.clear();
    values.clear();
    for (const auto& [c, v] : rows[i]) {
      columns.push_back(c);
      values.push_back(v);
    }
    check(MatSetValues(a, 1, &i, static_cast<PetscInt>(columns.size()), columns.data(),
                       values.data(), INSERT_VALUES),
          "MatSetValues");
  }
  check(MatAssemblyBegin(a, MAT_FINAL_ASSEMBLY), "assembly");
  check(MatAssemblyEnd(a, MAT_FINAL_ASSEMBLY), "assembly");
  check(MatSetOption(a, MAT_SYMMETRIC, PETSC_TRUE), "symmetric");
  check(MatSetOption(a, MAT_SPD, PETSC_TRUE), "spd");
  return a;
}

double relative_residual(Mat a, Vec x, Vec b) {
  Vec r;
  VecDuplicate(b, &r);
  MatMult(a, x, r);
  VecAYPX(r, -1.0, b);
  PetscReal rn = 0, bn = 0;
  VecNorm(r, NORM_2, &rn);
  VecNorm(b, NORM_2, &bn);
  VecDestroy(&r);
  return rn / bn;
}

// A direct solver: MUMPS Cholesky of `a`.
KSP direct(Mat a, double& factor_seconds) {
  KSP ksp;
  PC pc;
  check(KSPCreate(PETSC_COMM_WORLD, &ksp), "KSPCreate");
  check(KSPSetOperators(ksp, a, a), "KSPSetOperators");
  check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
  check(KSPGetPC(ksp, &pc), "KSPGetPC");
  check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "MUMPS");
  MPI_Barrier(PETSC_COMM_WORLD);
  const double start = MPI_Wtime();
  check(KSPSetUp(ksp), "MUMPS factorization");
  MPI_Barrier(PETSC_COMM_WORLD);
  factor_seconds = MPI_Wtime() - start;
  return ksp;
}

// The K0 factor as a preconditioner (PCSHELL).
PetscErrorCode apply_factor(PC pc, Vec x, Vec y) {
  void* context = nullptr;
  PCShellGetContext(pc, &context);
  return KSPSolve(static_cast<KSP>(context), x, y);
}

struct Solve {
  PetscInt iterations = 0;
  double seconds = 0, residual = 0;
};

Solve iterate(Mat a, Vec b, Vec x, const std::string& preconditioner, KSP k0_factor,
              bool warm) {
  KSP ksp;
  PC pc;
  KSPCreate(PETSC_COMM_WORLD, &ksp);
  KSPSetOperators(ksp, a, a);
  KSPSetType(ksp, KSPCG);
  KSPSetTolerances(ksp, 1e-11, 1e-300, PETSC_DEFAULT, 2000);
  KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED);
  KSPGetPC(ksp, &pc);
  if (preconditioner == "K0") {
    PCSetType(pc, PCSHELL);
    PCShellSetContext(pc, k0_factor);
    PCShellSetApply(pc, apply_factor);
  } else if (preconditioner == "gamg") {
    PCSetType(pc, PCGAMG);
  } else {
    PCSetType(pc, PCHYPRE);
    PCHYPRESetType(pc, "boomeramg");
  }
  KSPSetInitialGuessNonzero(ksp, warm ? PETSC_TRUE : PETSC_FALSE);
  KSPSetOptionsPrefix(ksp, (preconditioner + "_").c_str());
  KSPSetFromOptions(ksp);  // e.g. -K0_ksp_monitor_true_residual
  MPI_Barrier(PETSC_COMM_WORLD);
  const double start = MPI_Wtime();
  const PetscErrorCode code = KSPSolve(ksp, b, x);
  MPI_Barrier(PETSC_COMM_WORLD);
  Solve s;
  s.seconds = MPI_Wtime() - start;
  check(code, ("CG with " + preconditioner).c_str());
  KSPGetIterationNumber(ksp, &s.iterations);
  s.residual = relative_residual(a, x, b);
  KSPDestroy(&ksp);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  check(PetscInitialize(&argc, &argv, nullptr, nullptr), "PetscInitialize");
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  const std::string spacing = argc > 1 && argv[1][0] != '-' ? argv[1] : "2000";
  std::vector<int> removals;
  for (int i = 2; i < argc && argv[i][0] != '-'; ++i) removals.push_back(std::stoi(argv[i]));
  if (removals.empty()) removals = {1, 10, 100};

  // Every rank builds the model (replicated) and keeps its block of rows.
  const Scene scene = read_problem_file("problems/reference-3d.toml",
                                        {"lattice.spacing=" + spacing, "contact.enabled=false"});
  Model model = build_model(scene);
  prepare_supports(model, scene.source_path);
  StiffnessMatrix stiffness(model);
  const Vector zero = Vector::Zero(model.dofs().dof_count());
  stiffness.assemble(model, zero);
  const Rows k0_rows = rows_of(stiffness);
  const auto n = static_cast<PetscInt>(k0_rows.size());
  const PetscInt first = n * rank / ranks, last = n * (rank + 1) / ranks;

  // The bonds to remove: those crossing x = 30 km, uppermost first.
  std::vector<std::int64_t> fault;
  for (std::int64_t b = 0; b < model.lattice.bond_count(); ++b) {
    const auto& bond = model.lattice.bonds[b];
    const double xi = model.lattice.positions[bond.i].x(), xj = model.lattice.positions[bond.j].x();
    if ((xi - 30e3) * (xj - 30e3) < 0 && model.state(b) == PairState::intact) fault.push_back(b);
  }
  std::stable_sort(fault.begin(), fault.end(), [&](std::int64_t a, std::int64_t b) {
    const auto z = [&](std::int64_t k) {
      return model.lattice.positions[model.lattice.bonds[k].i].z() +
             model.lattice.positions[model.lattice.bonds[k].j].z();
    };
    return z(a) > z(b);
  });

  Mat k0 = petsc_matrix(k0_rows, first, last);
  Vec b, x0;
  MatCreateVecs(k0, &x0, &b);
  const Vector load = model.free_part(model.external_force);
  for (PetscInt i = first; i < last; ++i) VecSetValue(b, i, load[i], INSERT_VALUES);
  VecAssemblyBegin(b);
  VecAssemblyEnd(b);

  double factor_seconds = 0;
  KSP k0_factor = direct(k0, factor_seconds);
  double start = MPI_Wtime();
  KSPSolve(k0_factor, b, x0);
  const double solve_seconds = MPI_Wtime() - start;
  const double k0_residual = relative_residual(k0, x0, b);  // collective: on every rank
  if (rank == 0) {
    std::printf("3-D reference block at %s m: %lld free dofs, %zu bonds across x = 30 km; "
                "%d MPI rank(s)\n\n",
                spacing.c_str(), static_cast<long long>(n), fault.size(), ranks);
    std::printf("K0: MUMPS Cholesky %.3f s, one solve %.4f s, residual %.1e\n\n", factor_seconds,
                solve_seconds, k0_residual);
    std::printf("| r | CG + K0 factor: its | s | CG + GAMG (warm): its | s | CG + BoomerAMG (warm): "
                "its | s | fresh MUMPS factor s | + solve s |\n|---|---|---|---|---|---|---|---|---|\n");
  }
  for (const int r : removals) {
    if (r > static_cast<int>(fault.size())) break;
    {
      ModelEditor editor(model);  // the pre-cut stays cut; r fault bonds in all are removed
      for (int k = 0; k < r; ++k) editor.set_state(fault[k], PairState::open);
    }
    stiffness.assemble(model, zero);
    Mat kr = petsc_matrix(rows_of(stiffness), first, last);
    Vec x;
    VecDuplicate(x0, &x);
    VecSet(x, 0);
    const Solve by_factor = iterate(kr, b, x, "K0", k0_factor, false);
    VecCopy(x0, x);
    const Solve by_gamg = iterate(kr, b, x, "gamg", nullptr, true);
    VecCopy(x0, x);
    const Solve by_boomer = iterate(kr, b, x, "boomeramg", nullptr, true);
    double fresh_seconds = 0;
    KSP fresh = direct(kr, fresh_seconds);
    start = MPI_Wtime();
    KSPSolve(fresh, b, x);
    const double fresh_solve = MPI_Wtime() - start;
    const double worst = std::max({by_factor.residual, by_gamg.residual, by_boomer.residual,
                                   relative_residual(kr, x, b)});  // on every rank
    if (rank == 0) {
      std::printf("| %d | %d | %.3f | %d | %.3f | %d | %.3f | %.3f | %.4f |\n", r,
                  static_cast<int>(by_factor.iterations), by_factor.seconds,
                  static_cast<int>(by_gamg.iterations), by_gamg.seconds,
                  static_cast<int>(by_boomer.iterations), by_boomer.seconds, fresh_seconds,
                  fresh_solve);
      if (worst > 1e-10) std::printf("  (worst residual %.1e: above 1e-10)\n", worst);
    }
    KSPDestroy(&fresh);
    VecDestroy(&x);
    MatDestroy(&kr);
  }
  std::vector<double> peaks(static_cast<std::size_t>(ranks));
  const double mine = peak_mib();
  MPI_Gather(&mine, 1, MPI_DOUBLE, peaks.data(), 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  if (rank == 0) {
    std::printf("\npeak resident memory per rank, MiB:");
    for (const double p : peaks) std::printf(" %.0f", p);
    std::printf("\n");
  }
  KSPDestroy(&k0_factor);
  VecDestroy(&b);
  VecDestroy(&x0);
  MatDestroy(&k0);
  PetscFinalize();
  return 0;
}
