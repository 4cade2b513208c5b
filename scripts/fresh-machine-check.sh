#!/usr/bin/env bash
# The README's two commands on a fresh Debian 12 machine: a bare bookworm root
# (debootstrap --variant=minbase, plus git) from this machine's own Debian
# mirror, a clone of this repository's HEAD commit in it, then
# `bash scripts/demo.sh` and `bash scripts/test.sh` inside it (chroot), each
# timed. Not part of CI (it installs ~850 packages and builds everything twice:
# most of an hour on 2 cores). Run it before a stop that changes install-deps.sh,
# the scripts or the CMake requirements; record the figures in docs/fresh-machine.md.
#
# usage (as root): scripts/fresh-machine-check.sh [--setup-only | --test-only | --hardening-only] [WORK_DIR]
#   --setup-only  build the root, clone, run scripts/install-deps.sh, stop
#   --test-only   reuse the root a full run left (packages, builds), move its clone
#                 to HEAD and run only `bash scripts/test.sh` (to finish a run that
#                 was stopped during test.sh, without an hour of set-up again)
#   --hardening-only  as --test-only, but only test.sh's second half,
#                 `bash scripts/test-hardening.sh` (after a run whose first half passed),
#                 preceded by install-deps as in test.sh
#   WORK_DIR      where the root and the logs go (default /var/tmp/keyturn-fresh);
#                 its old root is deleted first
# It tests the committed HEAD, not uncommitted changes.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
setup_only=0
test_only=0
if [ "${1:-}" = "--setup-only" ]; then setup_only=1; shift; fi
hardening_only=0
if [ "${1:-}" = "--test-only" ]; then test_only=1; shift; fi
if [ "${1:-}" = "--hardening-only" ]; then test_only=1; hardening_only=1; shift; fi
work=${1:-/var/tmp/keyturn-fresh}
root=$work/root
src=/src/keyturn

say() { echo "fresh-machine-check: $*"; }
die() { say "$*" >&2; exit 1; }

[ "$(id -u)" -eq 0 ] || die "needs root (debootstrap, mount, chroot)"
commit=$(git -C "$repo" rev-parse HEAD)

# The first enabled Debian mirror serving bookworm, from deb822 .sources files or
# one-line sources.list entries; prints "URI FILE".
find_mirror() {
  local f
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    awk -v file="$f" 'BEGIN { RS = ""; FS = "\n" }
      { uri = ""; suite = 0; off = 0
        for (i = 1; i <= NF; i++) {
          if ($i ~ /^URIs:/) { sub(/^URIs:[ \t]*/, "", $i); split($i, a, /[ \t]+/); uri = a[1] }
          if ($i ~ /^Suites:/ && $i ~ /[ \t]bookworm([ \t]|$)/) suite = 1
          if ($i ~ /^Enabled:[ \t]*no/) off = 1 }
        if (uri != "" && suite && !off) { print uri, file; exit } }' "$f"
  done | head -1
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -f "$f" ] || continue
    awk -v file="$f" '$1 == "deb" { i = 2
        if ($2 ~ /^\[/) { while (i < NF && $i !~ /\]$/) i++; i++ }
        if ($(i + 1) == "bookworm") { print $i, file; exit } }' "$f"
  done | head -1
}
read -r mirror mirror_file < <(find_mirror | head -1) || true
[ -n "${mirror:-}" ] || die "no Debian bookworm mirror in /etc/apt/sources.list or /etc/apt/sources.list.d"

mounted=()
cleanup() {
  local i
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
    umount -R "${mounted[$i]}" 2> /dev/null || umount -l "${mounted[$i]}" 2> /dev/null || true
  done
}
trap cleanup EXIT
bind() {  # bind-mount the host's $1 at the same path in the root
  mkdir -p "$root$1"
  mount --rbind "$1" "$root$1"
  mount --make-rslave "$root$1" 2> /dev/null || true
  mounted+=("$root$1")
}

if [ "$test_only" -eq 1 ]; then
  [ -d "$root$src/.git" ] || die "--test-only needs the root of an earlier run at $root"
  if grep -q " $root/" /proc/mounts; then die "$root still has mounts; unmount them first"; fi
fi
# A root left by an interrupted run may still have mounts: never delete through them.
if [ "$test_only" -eq 0 ] && [ -d "$root" ]; then
  for m in sys dev proc; do umount -R "$root/$m" 2> /dev/null || true; done
  if grep -q " $root/" /proc/mounts; then die "$root still has mounts; unmount them first"; fi
  rm -rf "$root"
fi
mkdir -p "$work"
command -v debootstrap > /dev/null || {
  say "installing debootstrap"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends debootstrap > /dev/null
}

if [ "$test_only" -eq 0 ]; then
say "commit $commit, mirror $mirror ($mirror_file), root $root"
t0=$(date +%s)
debootstrap --variant=minbase --include=git,ca-certificates bookworm "$root" "$mirror" > "$work/debootstrap.log" 2>&1 ||
  die "debootstrap failed (log: $work/debootstrap.log)"
say "debootstrap: $(($(date +%s) - t0)) s"

# What an installed Debian machine has and a bare root lacks: the machine's own
# apt sources (updates and security too), name resolution, localhost in
# /etc/hosts (loopback tests), and a machine id (libdbus, loaded by Qt, aborts
# without one).
if [[ $mirror_file == *.sources ]]; then
  rm -f "$root/etc/apt/sources.list"
  cp "$mirror_file" "$root/etc/apt/sources.list.d/"
else
  grep -hE '^\s*deb\s.*\sbookworm(-updates|-security)?\s' "$mirror_file" > "$root/etc/apt/sources.list"
fi
cp /etc/resolv.conf "$root/etc/resolv.conf"
grep -qs localhost "$root/etc/hosts" || printf '127.0.0.1\tlocalhost\n::1\tlocalhost ip6-localhost\n' >> "$root/etc/hosts"
od -An -N16 -tx1 /dev/urandom | tr -d ' \n' > "$root/etc/machine-id"
fi

bind /proc
bind /sys
bind /dev  # with /dev/pts (pseudo-terminals for the Modbus RTU tests) and /dev/shm

if [ "$test_only" -eq 1 ]; then
  git -C "$root$src" fetch --quiet "$repo" "$commit"
  git -C "$root$src" checkout --quiet --detach "$commit"
  say "reusing $root, its clone moved to $commit"
else
  mkdir -p "$root$(dirname "$src")"
  git clone --quiet "$repo" "$root$src"
  git -C "$root$src" checkout --quiet --detach "$commit"
fi

# A login's environment, not this shell's: only PATH, HOME, locale and a proxy if
# this machine reaches its mirror through one.
in_root() {
  local env=(PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 TERM=dumb)
  local v
  for v in http_proxy https_proxy no_proxy HTTP_PROXY HTTPS_PROXY NO_PROXY; do
    [ -n "${!v:-}" ] && env+=("$v=${!v}")
  done
  chroot "$root" /usr/bin/env -i "${env[@]}" /bin/bash -c "cd $src && $1"
}

failed=0
timed() {  # timed NAME COMMAND: runs COMMAND in the root, logs to WORK/NAME.log
  local name=$1 cmd=$2 start rc=0 s
  start=$(date +%s)
  in_root "$cmd" > "$work/$name.log" 2>&1 || rc=$?
  s=$(($(date +%s) - start))
  printf 'fresh-machine-check: %-22s exit %d in %dm%02ds (log: %s)\n' "$cmd" "$rc" $((s / 60)) $((s % 60)) "$work/$name.log"
  if [ "$rc" -ne 0 ]; then
    failed=$((failed + 1))
    tail -n 15 "$work/$name.log" | sed 's/^/  | /'
  fi
}

if [ "$setup_only" -eq 1 ]; then
  timed install-deps "bash scripts/install-deps.sh"
  say "packages installed in the root: $(chroot "$root" dpkg-query -W -f='${Status}\n' | grep -c 'install ok installed')"
elif [ "$hardening_only" -eq 1 ]; then
  # install-deps first, as test.sh does: the clone's HEAD may ask for packages the root lacks
  timed test-hardening "bash scripts/install-deps.sh && bash scripts/test-hardening.sh"
elif [ "$test_only" -eq 1 ]; then
  timed test "bash scripts/test.sh"
else
  timed demo "bash scripts/demo.sh"
  timed test "bash scripts/test.sh"
fi
say "$(date -u +%Y-%m-%dT%H:%MZ), commit ${commit:0:7}: $failed failed"
test "$failed" -eq 0
