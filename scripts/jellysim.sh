#!/usr/bin/env bash
# One entry point for a fresh Debian 12 machine: installs what is missing (apt-get), builds, then
#   scripts/jellysim.sh run [jellysim run options]   runs the main job on the built-in default scene
#   scripts/jellysim.sh test                         runs the whole test suite: Release (gcc), then
#                                                    ASan+UBSan (clang, a short libFuzzer run included),
#                                                    then the threaded library tests under ThreadSanitizer
#                                                    (clang; only their modules are built, ~3.5 min cold on
#                                                    the shared 2 cores); every build with warnings as errors
#   scripts/jellysim.sh build                        only installs and builds
#   scripts/jellysim.sh tsan                         every threaded test under ThreadSanitizer, the command
#                                                    line's (threaded batch, determinism) included: it builds
#                                                    the whole program (~20 min cold on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(build-essential cmake pkg-config libeigen3-dev libtomlplusplus-dev nlohmann-json3-dev libcli11-dev
          libgtest-dev libgmock-dev libbenchmark-dev libplplot-dev plplot-driver-cairo fonts-dejavu-core
          libegl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri libpng-dev zlib1g-dev libstb-dev ffmpeg
          libglfw3-dev libimgui-dev xvfb xauth libfftw3-dev clang libclang-rt-14-dev libcereal-dev
          libopenmpi-dev openmpi-bin libnlopt-cxx-dev libopenexr-dev pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib
          blender)
JOBS=$(nproc 2>/dev/null || echo 2)

install_missing_packages() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "Installing Debian packages: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# build DIR [cmake options...]: configure once, then build incrementally; the log stays in DIR.
build() {
  local dir=$1; shift
  echo "Building in $dir ..."
  mkdir -p "$dir"
  if ! { cmake -S . -B "$dir" -Wno-dev "$@" && cmake --build "$dir" -j"$JOBS"; } >"$dir/build.log" 2>&1; then
    tail -n 60 "$dir/build.log" >&2
    echo "build failed (full log: $dir/build.log)" >&2
    exit 1
  fi
  grep -E 'warning:' "$dir/build.log" >&2 || true
}

# Every build of this script (and so CI) treats warnings as errors.
build_release() { build build/release -DCMAKE_BUILD_TYPE=Release -DJELLYSIM_WERROR=ON; }

# The ThreadSanitizer pass (clang, -fsanitize=thread, warnings as errors) builds only the named test
# programs, each with its own module's libraries (tests/CMakeLists.txt), and runs only the threaded
# tests. In `test`: the worker pool, the serial writer thread and the path chooser (core), the
# mobility table built on threads (coupling), the SPH evaluation and backward Euler on threads (sph),
# the 3D fluid's step on two threads (fluid3d), the 3D immersed boundary's spreading, interpolation and
# coupled step on two threads (ib3d).
# `tsan` adds the command line's threaded batch and one-versus-two-threads determinism runs, which
# need the program and so every module built under ThreadSanitizer (the batch's threaded runner is in
# `experiments`, nearly the whole program: too slow for `test`).
TSAN_LIBRARY_PROGRAMS=(test_core test_coupling test_sph test_fluid3d test_ib3d)
TSAN_LIBRARY_TESTS='^(WorkerPool|SerialWorker|PathChooser|Fluid3dThreads|Transfer3dThreads|ImmersedBoundary3dThreads)\.|^FftPressure3d\.RepeatedAndThreaded|^MobilityTable\.Threads|^SphFluid\.Threads|^SphScene\..*Threads|^SphBackwardEuler\.RunsAdaptively'
TSAN_CLI_TESTS='^BatchCli\.ThreadedBatch|^Determinism\..*Threads'
# build_tsan PROGRAM...
build_tsan() {
  if [ -f build/tsan/CMakeCache.txt ] && ! grep -q '^CMAKE_CXX_COMPILER:.*clang' build/tsan/CMakeCache.txt; then
    rm -rf build/tsan
  fi
  echo "Building in build/tsan ($*) ..."
  mkdir -p build/tsan
  if ! { CC=clang CXX=clang++ cmake -S . -B build/tsan -Wno-dev -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g1" \
           -DJELLYSIM_TSAN=ON -DJELLYSIM_WERROR=ON -DJELLYSIM_PYTHON=OFF -DJELLYSIM_BUILD_BENCH=OFF &&
         cmake --build build/tsan -j"$JOBS" --target "$@"; } >build/tsan/build.log 2>&1; then
    tail -n 60 build/tsan/build.log >&2
    echo "build failed (full log: build/tsan/build.log)" >&2
    exit 1
  fi
}
# run_tsan REGEX: the tests of build/tsan whose names match.
run_tsan() {
  TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/tests/tsan.supp" \
    ctest --test-dir build/tsan --output-on-failure -j"$JOBS" --timeout 900 -R "$1"
}
# The sanitizer pass is built with clang, which also builds the libFuzzer target (fuzz/): a cache
# made by another compiler is started afresh. The Python module is built there too (JELLYSIM_PYTHON=ON:
# its tests preload the ASan runtime into python3, docs/python.md).
build_sanitized() {
  if [ -f build/sanitize/CMakeCache.txt ] && ! grep -q '^CMAKE_CXX_COMPILER:.*clang' build/sanitize/CMakeCache.txt; then
    rm -rf build/sanitize
  fi
  CC=clang CXX=clang++ build build/sanitize -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g1" \
    -DJELLYSIM_SANITIZE=ON -DJELLYSIM_FUZZ=ON -DJELLYSIM_PYTHON=ON -DJELLYSIM_WERROR=ON
}

command=${1:-run}
[ $# -gt 0 ] && shift
install_missing_packages
case "$command" in
  build) build_release ;;
  run)
    build_release
    exec build/release/jellysim run "$@" ;;
  test)
    build_release
    echo "== tests (Release) =="
    ctest --test-dir build/release --output-on-failure -j"$JOBS" --timeout 600
    build_sanitized
    # Long physics studies (test names containing "Slow", e.g. ten swimming cycles) run in the Release
    # pass only: under the sanitizers they would take tens of minutes and add no memory coverage.
    echo "== tests (clang, AddressSanitizer + UndefinedBehaviorSanitizer, the fuzzer; *Slow* tests in Release only) =="
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
      LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp:print_suppressions=0 \
      ctest --test-dir build/sanitize --output-on-failure -j"$JOBS" --timeout 900 -E Slow
    build_tsan "${TSAN_LIBRARY_PROGRAMS[@]}"
    echo "== threaded library tests (clang, ThreadSanitizer) =="
    run_tsan "$TSAN_LIBRARY_TESTS" ;;
  tsan)
    build_tsan "${TSAN_LIBRARY_PROGRAMS[@]}" test_app
    echo "== threaded tests (clang, ThreadSanitizer) =="
    run_tsan "$TSAN_LIBRARY_TESTS|$TSAN_CLI_TESTS" ;;
  *) echo "usage: scripts/jellysim.sh [run [options] | test | build | tsan]" >&2; exit 2 ;;
esac
