#!/usr/bin/env bash
# Build the Debian package rigsim_<version>_<arch>.deb in build/package/package/ (docs/packaging.md):
# a release build of its own (build/package: no tests, no benches, the Debian layout), then CPack.
#   scripts/package.sh          build the package (installs dpkg-dev and file if missing)
#   scripts/package.sh --test   then install it in a fresh Debian 12 root and check it there
#                               (scripts/package-test.sh: root, debootstrap, Debian's mirror)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh --package
jobs=$(nproc 2>/dev/null || echo 2)
bash scripts/configure.sh build/package -DCMAKE_BUILD_TYPE=Release -DRIGSIM_WERROR=ON -DRIGSIM_TESTS=OFF \
  -DRIGSIM_BENCH=OFF -DRIGSIM_DEBIAN_LAYOUT=ON
cmake --build build/package -j"$jobs"
rm -f build/package/package/rigsim_*.deb
(cd build/package && cpack -G DEB >/dev/null)
deb=$(ls build/package/package/rigsim_*.deb)
echo "package: $deb ($(du -k "$deb" | cut -f1) KiB)"
if [ "${1:-}" = "--test" ]; then
  exec bash scripts/package-test.sh "$deb"
fi
