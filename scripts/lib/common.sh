# Shared by scripts/test and scripts/demo: install what is missing (Debian packages only) and
# build. Source it; it does nothing by itself.

DYNSLAM_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
DYNSLAM_BUILD="${DYNSLAM_BUILD:-$DYNSLAM_ROOT/build/release}"
DYNSLAM_JOBS="${DYNSLAM_JOBS:-2}"

# Every package dynslam needs to build, test and plot (docs/DEPENDENCIES.md says why).
DYNSLAM_PACKAGES=(
  cmake g++ make
  libceres-dev libeigen3-dev libsuitesparse-dev libopenblas0-pthread libgoogle-glog-dev libgflags-dev
  libgtest-dev libgmock-dev libbenchmark-dev nlohmann-json3-dev
  python3 python3-matplotlib python3-venv locales
  pybind11-dev python3-dev python3-numpy python3-pytest
  python3-distributed python3-scipy
  python3-plotly python3-pil chromium
)

log() { printf '[%s] %s\n' "$(basename "$0")" "$*" >&2; }

install_missing_packages() {
  local missing=()
  for package in "${DYNSLAM_PACKAGES[@]}" "$@"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$package")
    fi
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  log "installing Debian packages: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# configure_and_build [TARGET…]: everything when no target is named.
configure_and_build() {
  log "configuring $DYNSLAM_BUILD"
  cmake -S "$DYNSLAM_ROOT" -B "$DYNSLAM_BUILD" -DCMAKE_BUILD_TYPE=Release \
    -DDYNSLAM_BUILD_TESTS=ON -DDYNSLAM_BUILD_APPS=ON >/dev/null
  log "building with -j$DYNSLAM_JOBS"
  local targets=()
  for target in "$@"; do targets+=(--target "$target"); done
  cmake --build "$DYNSLAM_BUILD" -j"$DYNSLAM_JOBS" "${targets[@]}"
}
