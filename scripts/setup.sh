#!/usr/bin/env bash
# Installs everything the project needs on a Debian machine: the Debian packages (apt-get), a venv
# at .venv with the pinned Python packages, and the Unity wheel. Run again, it is quick and
# changes nothing.
set -euo pipefail
cd "$(dirname "$0")/.."

# libtbb12: ecospy's engine (the SSP master of tests/python/test_ssp.py); libsuitesparse-dev: KLU for
# bench-linear (the core's solvers against SUNDIALS' KLU; skipped by CMake without it); locales: the
# locale sources from which the tests build a decimal-comma locale (de_DE) with localedef;
# chromium, chromium-driver: the headless browser of tests/python/test_view.py (Selenium); npm
# (unless one is on PATH already, e.g. with a Node.js of its own): fetches three.js below
debian_packages=(cmake make g++ binutils valgrind libsundials-dev libeigen3-dev libsuitesparse-dev python3
                 python3-venv python3-dev libtbb12 locales chromium chromium-driver)
command -v npm >/dev/null || debian_packages+=(npm)
missing=()
for p in "${debian_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing Debian packages: ${missing[*]}"
  as_root=""; [ "$(id -u)" -eq 0 ] || as_root="sudo"
  $as_root apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $as_root apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# The venv is built from Debian's interpreter, whatever else is on PATH.
if [ ! -x .venv/bin/python ]; then
  echo "setup: creating .venv"
  /usr/bin/python3 -m venv .venv
fi
if ! cmp -s scripts/requirements.txt .venv/installed-requirements.txt; then
  echo "setup: installing Python packages (scripts/requirements.txt)"
  .venv/bin/pip install -q --disable-pip-version-check -r scripts/requirements.txt
  cp scripts/requirements.txt .venv/installed-requirements.txt
fi

# Unity 2.6.1 comes in the vyperling wheel; CMake extracts it and checks its sha256
# (cmake/FetchUnity.cmake).
if ! ls .cache/wheels/vyperling-0.0.4-*.whl >/dev/null 2>&1; then
  echo "setup: fetching Unity (vyperling==0.0.4) from PyPI"
  .venv/bin/pip download -q --disable-pip-version-check --no-deps --only-binary=:all: \
    -d .cache/wheels vyperling==0.0.4
fi

# three.js, the 3D library stewart.view inlines into its pages (docs/view.md): the npm package
# `three`, pinned and checked against the sha256 below, unpacked into .cache/three; the package
# build (python/CMakeLists.txt) installs its two module files, its orbit controls and its licence
# as package data.
three_version=0.187.0
three_sha256=ff540832ded0cfe919764d24a3d88f3e2a05f23303f876423e4f893841e90728
three_files=(build/three.core.js build/three.module.js examples/jsm/controls/OrbitControls.js LICENSE)
if [ "$(cat .cache/three/VERSION 2>/dev/null)" != "$three_version" ] ||
   ! (cd .cache/three && ls "${three_files[@]}" >/dev/null 2>&1); then
  echo "setup: fetching three@$three_version from the npm registry"
  rm -rf .cache/three .cache/npm && mkdir -p .cache/npm .cache/three
  (cd .cache/npm && npm pack --silent "three@$three_version" >/dev/null)
  echo "$three_sha256  .cache/npm/three-$three_version.tgz" | sha256sum --check --quiet
  tar -xzf ".cache/npm/three-$three_version.tgz" -C .cache/three --strip-components=1 \
    "${three_files[@]/#/package/}"
  echo "$three_version" > .cache/three/VERSION
fi

# The Python package `stewart` (pyproject.toml: the library through nanobind, the FMUs inside),
# built from this tree with the venv's build tools; reinstalled only when a source file is newer
# than the last install.
stamp=.venv/installed-stewart
if [ ! -f "$stamp" ] || [ -n "$(find pyproject.toml CMakeLists.txt csrc fmu python .cache/three/VERSION -newer "$stamp" -type f -print -quit)" ]; then
  echo "setup: installing the Python package stewart (pip install .)"
  .venv/bin/pip install -q --disable-pip-version-check --no-build-isolation --no-deps .
  touch "$stamp"
fi
