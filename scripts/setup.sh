#!/usr/bin/env bash
# Shared set-up for run.sh and test.sh: install missing Debian 12 packages, then configure and
# build (Release) in build/. Safe to run again: installed packages and a configured build are reused.
#   scripts/setup.sh [--with-paraview] [--tests-only]
# --with-paraview also installs Debian's ParaView (paraview, python3-paraview: pvbatch) and xvfb
# (Debian's pvbatch renders through X; without a display `tmdem render` runs it on an Xvfb of its own).
# The ctest tests ParaView.* (ParaView's readers on RESULT.xdmf) and ParaViewRender.* (`tmdem
# render`) need them and are skipped without them. ./test.sh passes --with-paraview; run.sh not.
# --tests-only builds what ctest runs (target ctest_programs), not the benchmark programs of bench/
# (./test.sh; 39 s of the 571 s of CPU of a whole Release build). run.sh builds everything.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
with_paraview=0
targets=()
for argument in "$@"; do
  case "$argument" in
    --with-paraview) with_paraview=1 ;;
    --tests-only) targets=(--target ctest_programs) ;;
    *) echo "setup: unknown option '$argument' (valid: --with-paraview, --tests-only)" >&2; exit 2 ;;
  esac
done

packages=(build-essential cmake pkg-config libsundials-dev libsuitesparse-dev libeigen3-dev
          libhdf5-dev libgtest-dev libbenchmark-dev libtomlplusplus-dev libcli11-dev
          nlohmann-json3-dev libfclib-dev libhypre-dev python3-matplotlib python3-h5py python3-siconos
          openmpi-bin  # mpirun: heating over MPI (docs/scale-out.md) and its test, skipped without it
          python3-pybind11 python3-pytest
          liggghts lammps  # real DEM codes whose packings and forces the suite imports (docs/import-dem.md)
          clang-14 libclang-rt-14-dev  # clang: the sanitizer build and libFuzzer (build-asan/)
          ninja-build)  # the generator of new build folders (below)
[ "$with_paraview" -eq 1 ] && packages+=(paraview python3-paraview xvfb xauth)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi

# GNU nproc answers OMP_NUM_THREADS (and OMP_THREAD_LIMIT) when set: test.sh exports
# OMP_NUM_THREADS=1 for its test programs, so from d54e329 on its build ran at -j 1 on 2 cores
# (clean-clone ./test.sh at 2e8464b: 579 s wall for 569 s CPU). Count the cores without them.
jobs="$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)"
# Ninja for a new build folder (one already configured keeps its generator): it compiles a
# program's or library's sources while the libraries it links are still being built, where make
# waits for them. With one unity batch per target the libraries form a chain (mechanics -> scene
# -> bridge -> run -> studies -> app) that make had built with one core idle: ./test.sh's Release
# build took 235 s wall with make, 188 s with Ninja (390 and 365 s of CPU, load 1.1-1.9).
generator=()
[ -f "$root/build/CMakeCache.txt" ] || generator=(-G Ninja)
cmake -S "$root" -B "$root/build" ${generator[@]+"${generator[@]}"} -DCMAKE_BUILD_TYPE=Release >&2
cmake --build "$root/build" -j "$jobs" ${targets[@]+"${targets[@]}"} >&2
