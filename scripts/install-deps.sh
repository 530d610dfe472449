#!/usr/bin/env bash
# Install the Debian 12 packages mo2d needs, but only those that are missing.
# Idempotent and silent when everything is already installed.
#   ./scripts/install-deps.sh            everything: the test suite, benchmarks, Python module, docs
#                                        (scripts/test.sh)
#   ./scripts/install-deps.sh --minimal  only what the libraries and the mo2d command link
#                                        (scripts/quickstart.sh)
set -euo pipefail

minimal=0
case "${1:-}" in
  "") ;;
  --minimal) minimal=1 ;;
  *) echo "usage: $0 [--minimal]" >&2; exit 2 ;;
esac

# the libraries (mo2d, mo2d_scene, mo2d_render, mo2d_box2d) and the mo2d command (target mo2d_cli)
packages=(
  build-essential cmake g++  # toolchain (GCC 12, CMake 3.25)
  libeigen3-dev              # Eigen 3.4: dense linear algebra of the core library
  libsundials-dev            # SUNDIALS 6.4: forward dynamics (CVODE)
  libsuitesparse-dev         # SuiteSparse 5.12 (KLU, SPQR, CHOLMOD): sparse LU and QR of large models
  libbox2d-dev               # Box2D 2.4.1: the cross-check (mo2d_box2d)
  libcairo2-dev              # Cairo 1.16: rendering (mo2d_render)
  zlib1g-dev                 # zlib: mo2d_render's PNG encoder (faster than Cairo's own writer)
  pkg-config                 # finds Cairo for CMake (pkg_check_modules)
  fonts-dejavu-core          # DejaVu Sans: the text of frames and plots
  libyaml-cpp-dev            # yaml-cpp 0.7: scene files (mo2d_scene, line/column of every node)
  libcli11-dev               # CLI11 2.1 (header-only): the mo2d command line
  nlohmann-json3-dev         # nlohmann-json 3.11 (header-only): JSON run summaries of mo2d
)
# the rest: tests, benchmarks, style checks, the Python module and its tests, the API reference
[[ $minimal == 1 ]] || packages+=(
  libavcodec-dev libavformat-dev libswscale-dev libavutil-dev  # FFmpeg 5.1: render --animate
  libnlopt-dev               # NLopt 2.7: mo2d optimize (optional: without it the command says so)
  libgtest-dev               # GoogleTest: tests/
  libbenchmark-dev           # Google Benchmark: bench/
  clang-format clang-tidy    # LLVM 14: scripts/check-style.sh (.clang-format, .clang-tidy)
  pybind11-dev               # pybind11 2.10 (CMake config): the Python module mo2d (python/)
  python3-dev                # Python.h and libpython of Debian's python3 3.11: the module's build
  python3-pybind11           # pybind11's Python side (pybind11.get_cmake_dir, its headers)
  python3-numpy              # NumPy 1.24: results as arrays (r.t, r.efforts)
  python3-pytest             # pytest 7.2: tests/python (run from ctest)
  python3-dask               # Dask 2022.12: mo2d.sweep, mo2d sweep
  python3-distributed        # dask.distributed 2022.12: LocalCluster, Client, dask scheduler/worker
  python3-pandas             # pandas 1.5: Result.to_pandas(), the table of a sweep
  python3-matplotlib         # matplotlib 3.6: the example script of docs/python.md (Agg backend)
  doxygen                    # Doxygen 1.9.4: the API reference (mo2d_docs) and its test docs.api
  chromium                   # headless Chromium: the viewer page tested in a real browser (view.browser_*)
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [[ "$status" == installed ]] || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "install-deps: installing ${missing[*]}"
sudo=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: not root and no sudo" >&2; exit 1; }
  sudo=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
