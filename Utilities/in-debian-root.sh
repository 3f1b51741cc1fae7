#!/usr/bin/env bash
# Runs a command of this repository inside a clean Debian root of another release, as root: the
# way to build and test vtkSAVR on Debian 13 from a Debian 12 machine (or the other way round).
#
#   bash Utilities/in-debian-root.sh RELEASE COMMAND...     # e.g. trixie bash Utilities/run-tests.sh
#
# The root is made with debootstrap (minbase) from the mirror that this machine's apt uses, once,
# into $SAVR_DEBIAN_ROOTS/RELEASE (default /var/cache/vtksavr): like the packages apt installs on
# the machine itself, what the command installs there stays for the next run. The repository's
# files (tracked and untracked, not ignored) are copied to /vtkSAVR inside the root, keeping their
# times so that builds there stay incremental; the copy starts afresh when it came from another
# checkout. /dev, /dev/pts, /dev/shm, /proc and /sys are bound for the command (Xvfb, MPI and
# package scripts need them) and unbound when it ends, however it ends.
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 RELEASE COMMAND..." >&2; exit 2; }
release=$1
shift
cd "$(dirname "$0")/.."
source_dir=$(pwd)
roots=${SAVR_DEBIAN_ROOTS:-/var/cache/vtksavr}
root="$roots/$release"
export DEBIAN_FRONTEND=noninteractive

# Binds left under the root by a run that was killed are undone first: nothing below removes
# files through them (and rm stays on the root's own file system besides).
unbind_under() {
  local target
  awk -v under="$1/" 'index($2, under) == 1 { print $2 }' /proc/mounts | sort -r |
    while read -r target; do umount -l "$target" || true; done
}
unbind_under "$root"

# 1. The root, made once. A root whose debootstrap did not finish (no stamp) is made again.
if [ ! -f "$root/.vtksavr-bootstrapped" ]; then
  if ! command -v debootstrap >/dev/null; then
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends debootstrap
  fi
  # The mirror that apt's own sources name: the archive of this machine's release (apt reads
  # its sources itself, comments and both file formats; the security archive serves other
  # suites).
  own=$(. /etc/os-release && echo "${VERSION_CODENAME:-}")
  mirror=$(apt-get indextargets --format '$(RELEASE) $(REPO_URI)' |
    awk -v own="$own" '$1 == own { print $2; exit }')
  [ -n "$mirror" ] || { echo "in-debian-root: no Debian mirror in apt's sources" >&2; exit 1; }
  echo "in-debian-root: making a $release root in $root from $mirror"
  rm -rf --one-file-system "$root"
  mkdir -p "$roots"
  debootstrap --variant=minbase "$release" "$root" "$mirror"
  touch "$root/.vtksavr-bootstrapped"
fi
cp /etc/resolv.conf "$root/etc/resolv.conf"

# 2. The repository's files, copied in. A copy from another checkout starts afresh, so that files
# deleted since cannot linger; from the same checkout only what changed is rebuilt.
work="$root/vtkSAVR"
if [ "$(cat "$work/.vtksavr-source" 2>/dev/null)" != "$source_dir" ]; then
  rm -rf --one-file-system "$work"
fi
mkdir -p "$work"
git ls-files -z --cached --others --exclude-standard |
  while IFS= read -r -d '' f; do [ -e "$f" ] && printf '%s\0' "$f"; done |
  tar -c --null -T - -f - | tar -x -f - -C "$work"
echo "$source_dir" > "$work/.vtksavr-source"

# 3. The command, with the kernel's file systems bound and unbound after.
mounted=()
unbind() {
  local i
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
    umount -l "${mounted[i]}" 2>/dev/null || true
  done
}
trap unbind EXIT
for m in dev dev/pts dev/shm proc sys; do
  mkdir -p "$root/$m"
  mount --bind "/$m" "$root/$m"
  mounted+=("$root/$m")
done
echo "in-debian-root: $release: $*"
chroot "$root" /usr/bin/env -i HOME=/root LANG=C.UTF-8 TERM="${TERM:-dumb}" \
  PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
  DEBIAN_FRONTEND=noninteractive CI="${CI:-}" \
  SAVR_SKIP_SANITIZE="${SAVR_SKIP_SANITIZE:-}" SAVR_SKIP_PARAVIEW="${SAVR_SKIP_PARAVIEW:-}" \
  /bin/bash -c 'cd /vtkSAVR && exec "$@"' in-debian-root "$@"
