# Sourced by the other scripts: installs the Debian packages the project needs when missing.
slc_packages=(cmake ninja-build g++ pkg-config libcli11-dev nlohmann-json3-dev libfmt-dev
              libcairo2-dev libmuparser-dev libgtest-dev libgmock-dev libbenchmark-dev clang-format
              python3 libopenvdb-dev libeigen3-dev)
# The Python package (scripts/python-env): Debian's interpreter, pybind11, numpy, pytest.
slc_python_packages=(python3-dev python3-venv python3-setuptools python3-wheel python3-pybind11
                     pybind11-dev python3-numpy python3-pytest python3-matplotlib python3-pandas
                     python3-distributed)
# The benchmarks' peers, measured beside slc in the same run (scripts/bench): CGAL's AABB_tree,
# OpenVDB's level-set advection (OpenVDB itself is in slc_packages: the library reads and writes
# its files).
slc_bench_packages=(libcgal-dev libopenvdb-dev)

slc_install_deps() {
  local missing=()
  for p in "${slc_packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "installing: ${missing[*]}" >&2
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
}
