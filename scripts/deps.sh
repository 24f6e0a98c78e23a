#!/usr/bin/env bash
# Install the Debian packages rigsim builds and tests with, if any is missing (apt-get, as root
# or with sudo). Run by scripts/run.sh and scripts/test.sh; safe to run again.
#   scripts/deps.sh          what building and running rigsimd needs (g++, CMake, Ninja, the
#                            libraries)
#   scripts/deps.sh --test   that and what the test suite needs: clang with its sanitizer
#                            runtime (libclang-rt-14-dev), symbolizer (llvm) and linker (lld)
#                            for the ASan + UBSan pass, python3-serial (the pyserial e2e test), python3-pytest
#                            (the tests of python/rigsim and its plugin), python3-venv (the
#                            offline `pip install ./python` test), python3-mypy (the package's
#                            type hints, checked with mypy --strict), chromium and chromium-driver
#                            (the live view in a headless browser, tests/e2e/live_view_browser.py)
#   scripts/deps.sh --package  what scripts/package.sh needs besides the build's: dpkg-dev
#                            (dpkg-shlibdeps finds the package's library dependencies) and file
#                            (CPack's DEB generator finds the programs to strip with it)
set -euo pipefail

packages=(g++ make cmake ninja-build libboost-dev libeigen3-dev libspdlog-dev nlohmann-json3-dev catch2
  python3)
if [ "${1:-}" = "--test" ]; then
  packages+=(clang libclang-rt-14-dev llvm lld python3-serial python3-pytest python3-venv python3-mypy
    chromium chromium-driver)
elif [ "${1:-}" = "--package" ]; then
  packages+=(dpkg-dev file)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "rigsim: installing Debian packages: ${missing[*]}" >&2
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "rigsim: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
    sudo="sudo"
  fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
