#!/usr/bin/env bash
# Installs every build, test and runtime dependency of ramap from Debian 12's packages.
# Idempotent: packages already present are left alone; safe to run again.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  colmap                      # the reference BA mapper and feature pipeline we compare with
  libceres-dev                # optional bundle adjustment
  libeigen3-dev
  libopencv-dev               # feature extraction / matching for image-list input
  libsuitesparse-dev          # CHOLMOD for the sparse normal equations
  libblas-dev                 # cblas.h: SGEMM for descriptor matching and image retrieval
  libopenblas0-pthread        # BLAS for CHOLMOD's dense kernels (Debian's alternatives pick it
                              # over ATLAS): translation averaging ~3x faster on 2 cores
  libgeographiclib-dev        # WGS84 <-> local frames
  libopengv-dev               # Kneip's relative-pose solvers
  libsqlite3-dev sqlite3      # COLMAP databases
  libgtest-dev libgmock-dev   # tests
  libcli11-dev                # command-line options
  nlohmann-json3-dev          # reports and summaries
  libspectra-dev              # sparse eigenvalues (Fiedler value of the certificate)
  libexiv2-dev                # EXIF focal length and GPS
  clang libclang-rt-14-dev    # libFuzzer and the sanitizers for the readers' fuzz harnesses
  python3-dev pybind11-dev    # the Python module, `import ramap`
  python3-numpy python3-pytest  # its arrays and its tests
  exiv2 python3-opencv        # scripts/make_internet_sets.py: the internet-conditions benchmark sets
  chromium                    # the browser test of report.html (tests/browser)
)

# The browser test's driver, playwright-core, at the version tests/browser/package-lock.json pins
# (npm's registry; it drives Debian's Chromium and downloads no browser of its own).
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi

install_browser_test_driver() {
  local dir
  dir=$(cd "$(dirname "$0")/../tests/browser" && pwd)
  if [[ -d $dir/node_modules/playwright-core ]]; then return; fi
  if ! command -v npm >/dev/null; then
    ${SUDO:-} apt-get update -qq
    DEBIAN_FRONTEND=noninteractive ${SUDO:-} apt-get install -y -qq --no-install-recommends nodejs npm
  fi
  echo "install-deps: npm ci in $dir"
  npm ci --prefix "$dir" --ignore-scripts --no-audit --no-fund >/dev/null
}

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages already installed"
  install_browser_test_driver
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
install_browser_test_driver
