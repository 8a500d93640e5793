#!/usr/bin/env bash
# Installs lgi's build and test dependencies from Debian 12's packages.
# Safe to run twice: apt-get install is idempotent, and nothing is installed
# when every package is already present.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev            # Eigen 3.4
  libboost-dev             # Boost 1.74 headers: Odeint, Math
  catch2                   # Catch2 2.13 (v2)
  libhdf5-dev hdf5-tools   # HDF5 1.10, C and high-level API; h5dump for inspection
  libcli11-dev             # CLI11
  libtomlplusplus-dev      # toml++
  libbenchmark-dev         # Google Benchmark
  libxsimd-dev             # xsimd 8 (header-only): the ensemble stepper's SIMD lanes
  clang libclang-rt-14-dev  # the fuzz preset: libFuzzer harnesses with ASan + UBSan (scripts/fuzz.sh)
  libomp-14-dev            # OpenMP for clang: the fuzz preset builds lgi's library for fuzz_command_line
  valgrind                 # memcheck of short simulate runs (CTest valgrind_simulate_*)
  libopenmpi-dev openmpi-bin  # MPI for `mpirun -np K lgi sweep` (-DLGI_MPI=ON; the lgi-mpi test build)
  python3-matplotlib python3-h5py python3-numpy  # Debian's /usr/bin/python3 for plots
  python3-pil                                     # GIF animations (matplotlib's PillowWriter)
  python3-pytest                                  # tests/python (CTest scripts_pytest): the scripts as a user runs them
  pybind11-dev python3-pybind11 python3-dev        # the Python module `lgi` (python/; CTest python_module)
  python3-scipy                                   # tests/python: reference integrations in the module tests
  python3-mpmath                                  # tests: high-precision reference values
  python3-nbconvert python3-ipykernel             # CTest notebook_*: examples/notebooks executed headless
  libspectra-dev                                  # Spectra (header-only, over Eigen): sparse eigensolvers of lgi quantum
  latexmk texlive-latex-base texlive-latex-recommended texlive-fonts-recommended lmodern  # the paper (scripts/build_paper.sh)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed" >&2
  exit 0
fi

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
