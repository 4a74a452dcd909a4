#!/usr/bin/env bash
# Installs the Debian 12 packages latfrac needs to build, test and run, when they are missing.
# Safe to run repeatedly: it installs nothing when every package is already present.
set -euo pipefail

packages=(
  build-essential cmake pkg-config git   # (GCC brings OpenMP: omp.h and libgomp, the bond sweeps' threads)
  libsundials-dev            # KINSOL (Newton) and CVODE
  libsuitesparse-dev         # CHOLMOD sparse Cholesky (with METIS); UMFPACK LU (friction)
  libopenblas0-pthread       # fast BLAS for CHOLMOD's supernodal kernels
  libeigen3-dev
  libcgal-dev                # random lattices: Delaunay triangulations (with GMP, MPFR, Boost)
  libhdf5-dev                # result files
  catch2                     # unit tests (v2)
  libtomlplusplus-dev        # problem files
  libcli11-dev               # command line
  libcairo2-dev              # pictures: PNG, SVG and PDF (Cairo)
  fonts-dejavu-core          # the pictures' font (DejaVu Sans)
  libexpat1-dev              # the picture tests parse the SVG files
  mpi-default-dev            # SUNDIALS' CMake config asks for MPI
  python3                    # the CLI tests validate JSON output with it
  hdf5-tools                 # h5dump: the restart tests and scripts/event-lists.sh read event lists
  bc                         # the restart tests time their stops
  libpetsc-real-dev          # solver.backend = "petsc" (src/solvers/petsc_backend.cpp), bench_petsc
  libmumps-dev libhypre-dev  # (PETSc's direct and multigrid solvers, named for clarity)
  openmpi-bin                # mpirun: the petsc backend on several ranks, its tests (ctest -L backend)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  echo "install-deps: installing ${missing[*]}" >&2
  if [ "$(id -u)" -ne 0 ]; then SUDO=sudo; else SUDO=; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
