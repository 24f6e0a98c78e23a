#!/usr/bin/env bash
# The install test of the Debian package (docs/packaging.md#the-install-test): in a fresh, minimal
# Debian 12 root (debootstrap --variant=minbase, made once and copied for each run), install the
# package with dpkg -i (apt-get then brings what it depends on, and man-db and systemd for the
# checks), and check from the installed files alone: rigsimd --version, man -w for the three man
# pages, systemd-analyze verify of rigsim@.service, the Python package and its pytest plugin under
# Debian's python3, bash completion, and the default rig run from /usr/share/rigsim as an
# unprivileged user with --pty-group, a member of the group talking to it over its pty.
# Needs root (debootstrap, chroot, mounts) and Debian's package mirror.
#   scripts/package-test.sh [DEB]    (default: build/package/package/rigsim_*.deb)
set -euo pipefail
cd "$(dirname "$0")/.."
deb=$(realpath "${1:-$(ls -t build/package/package/rigsim_*.deb | head -n 1)}")
[ "$(id -u)" -eq 0 ] || { echo "package-test: needs root (debootstrap, chroot)" >&2; exit 2; }
base=${RIGSIM_DEBIAN_ROOT_CACHE:-/var/tmp/rigsim-debian12-minbase}
if [ ! -f "$base/.ready" ]; then
  command -v debootstrap >/dev/null || { apt-get update -qq && apt-get install -y -qq debootstrap >/dev/null; }
  mirror=$(sed -n 's/^URIs: *\(.*\/debian\)$/\1/p' /etc/apt/sources.list.d/debian.sources 2>/dev/null | head -n 1)
  [ -n "$mirror" ] || mirror=$(awk '$1=="deb"{print $2; exit}' /etc/apt/sources.list 2>/dev/null)
  [ -n "$mirror" ] || mirror=http://deb.debian.org/debian
  rm -rf "$base"; mkdir -p "$base"
  echo "package-test: making a minimal Debian 12 root in $base (once)"
  debootstrap --variant=minbase bookworm "$base" "$mirror" >"$base.log" 2>&1 ||
    { echo "package-test: debootstrap failed, see $base.log" >&2; exit 2; }
  # debootstrap wrote "deb $mirror bookworm main" to its sources.list: the root stays Debian 12
  # whatever release the host runs.
  touch "$base/.ready"
fi
root=$(mktemp -d /var/tmp/rigsim-package-test.XXXXXX)
cleanup() {
  for m in dev/pts dev proc sys; do umount -l "$root/$m" 2>/dev/null || true; done
  rm -rf --one-file-system "$root"
}
trap cleanup EXIT
cp -a "$base/." "$root/"
for m in proc sys dev dev/pts; do mkdir -p "$root/$m"; mount --bind "/$m" "$root/$m"; done
cp /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true
cp "$deb" "$root/tmp/"
echo "package-test: $(basename "$deb") in a fresh Debian 12 root"
chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root DEBIAN_FRONTEND=noninteractive \
  DEB="/tmp/$(basename "$deb")" bash -s <<'CHECKS'
set -euo pipefail
step() { echo "== $*"; }
step "dpkg -i, then apt-get -f install for its dependencies"
apt-get update -qq
dpkg -i "$DEB" >/dev/null 2>&1 || true
apt-get install -y -qq -f --no-install-recommends >/dev/null
dpkg -s rigsim | grep -E '^(Status|Version|Depends):'
apt-get install -y -qq --no-install-recommends man-db systemd >/dev/null
step "rigsimd --version"
rigsimd --version
step "man -w"
man -w rigsimd rigsimctl && man -w 5 rigsim-rig
man rigsimd 2>/dev/null | grep -q -- '--pty-group' && echo "man rigsimd renders, --pty-group in it"
step "systemd-analyze verify rigsim@default.service"
systemd-analyze verify rigsim@default.service && echo "verified"
step "Debian's python3 imports rigsim and sees its pytest plugin"
python3 -c 'import rigsim, importlib.metadata as m; eps = m.entry_points(group="pytest11"); print("rigsim", m.version("rigsim"), [e.value for e in eps])'
step "bash completion"
bash -c 'source /usr/share/bash-completion/completions/rigsimd; COMP_WORDS=(rigsimd --pty-g); COMP_CWORD=1; _rigsimd; echo "rigsimd --pty-g<TAB>: ${COMPREPLY[*]}"; [ "${COMPREPLY[*]}" = --pty-group ]'
step "the default rig from /usr/share/rigsim, as nobody with --pty-group dialout"
useradd --no-create-home --groups dialout rigsim-client
install -d -o nobody -m 0755 /run/rigsim-test
# Ephemeral ports: a rigsimd on the host (rigsim@default) may hold the default rig's.
setpriv --reuid=nobody --regid=nogroup --groups=dialout --inh-caps=-all \
  rigsimd --config /usr/share/rigsim/default.json --ephemeral-ports --pty-dir /run/rigsim-test \
  --pty-group dialout --endpoints-json /run/rigsim-test/endpoints.json 2>/tmp/rigsimd.log &
pid=$!
for _ in $(seq 100); do [ -f /run/rigsim-test/endpoints.json ] && break; sleep 0.1; done
[ -f /run/rigsim-test/endpoints.json ] || { echo "rigsimd did not start:"; cat /tmp/rigsimd.log; exit 1; }
ls -lL /run/rigsim-test/mcs0
rigsimctl --endpoints /run/rigsim-test/endpoints.json rig --format table
setpriv --reuid=rigsim-client --regid=rigsim-client --init-groups python3 - <<'PY'
import os, select, termios, tty
fd = os.open("/run/rigsim-test/mcs0", os.O_RDWR | os.O_NOCTTY)
tty.setraw(fd)
os.write(fd, b":GSI\n")
answer = b""
while not answer.endswith(b"\n") and select.select([fd], [], [], 5)[0]:
    answer += os.read(fd, 64)
print("rigsim-client (group dialout) over the pty: :GSI ->", answer)
assert answer.startswith(b":ID"), answer
PY
kill "$pid"; wait "$pid"; echo "rigsimd exited $?"
step "all checks passed"
CHECKS
