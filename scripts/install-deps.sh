#!/usr/bin/env bash
# Installs fetic's dependencies from Debian 12's packages.
#   scripts/install-deps.sh          what building and running the program needs
#                                    (README's first command, scripts/setup.sh)
#   scripts/install-deps.sh --all    that, and what the tests, benchmarks, package check,
#                                    fuzzing and window tests need (scripts/test.sh, CI)
set -euo pipefail
program=(
  cmake ninja-build g++ pkg-config
  libeigen3-dev libsuitesparse-dev          # linear algebra, CHOLMOD, SuiteSparseQR
  libtomlplusplus-dev libcli11-dev nlohmann-json3-dev   # scenes, command line, results
  libimgui-dev libglfw3-dev libstb-dev      # window, overlay, text and PNG reading
  libspng-dev                               # PNG frames (8x faster than stb_image_write)
  libegl-dev libegl1-mesa-dev libgl-dev libgles-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri
  fonts-dejavu-core                         # text in rendered frames
  zlib1g-dev                                # compressed ParaView (.vtu) output
)
rest=(
  catch2 libcgal-dev libgmp-dev libmpfr-dev # tests: Catch2, CGAL's exact QP solver
  coinor-libipopt-dev                       # benchmark: a general-purpose QP solver
  xvfb xauth xdotool                        # window tests
  ffmpeg                                    # movies (the program runs without; tests make movies)
  python3-vtk9                              # tests: VTK's reader checks the .vtu files
  # distributed solves (mpirun -np N fetic solve) and their tests: the program builds
  # without MPI (one process only), and Open MPI is 45 packages; CMake finds it once here
  libopenmpi-dev openmpi-bin
  dpkg-dev file lintian                     # cpack -G DEB (dpkg-shlibdeps), the package check
  # scripts/fuzz.sh: clang with libFuzzer and the ASan/UBSan runtimes for clang, and
  # llvm-symbolizer for readable crash stacks (g++'s sanitizers need nothing more)
  clang-14 libclang-rt-14-dev llvm-14
)
packages=("${program[@]}")
[ "${1:-}" = "--all" ] && packages+=("${rest[@]}")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
