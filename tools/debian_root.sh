# A minimal Debian root for checks that need a really fresh machine (sourced, not run):
# tools/check_fresh_debian.sh (the README's two commands, on Debian 12 and 13) and tests/gradescope
# (the Gradescope archive, Debian 12). Made with Debian's mmdebstrap; /proc, /sys and /dev bound in;
# removed with its mounts.
#
#   debian_root_usable              0 when this host can make one (root, mmdebstrap), else prints why
#   debian_root_make ROOT LOG [PKG,...] [SUITE]
#                                   mmdebstrap --variant=apt SUITE ROOT, extra packages; SUITE is
#                                   bookworm (Debian 12, the default) or trixie (Debian 13)
#   debian_root_mount ROOT          binds /proc, /sys, /dev, copies resolv.conf (for apt), writes
#                                   the /etc/hosts an installed system has
#   debian_root_run ROOT COMMAND    bash -c COMMAND inside, with a clean root environment
#   debian_root_release ROOT DIR    unmounts what debian_root_mount bound, then removes DIR (which
#                                   holds ROOT) unless a mount is left or DEBIAN_ROOT_KEEP=1
# shellcheck shell=bash

debian_root_mounts=()

debian_root_usable() {
  if [ "$(id -u)" -ne 0 ]; then
    echo "needs root (mmdebstrap, chroot and bind mounts)"
    return 1
  fi
  if ! command -v mmdebstrap >/dev/null; then
    echo "mmdebstrap is not installed (Debian package mmdebstrap)"
    return 1
  fi
  return 0
}

debian_root_make() {
  local root=$1 log=$2 include=ca-certificates${3:+,$3} suite=${4:-bookworm}
  mmdebstrap --quiet --variant=apt --include="$include" "$suite" "$root" >"$log" 2>&1
}

# The Debian release a suite name stands for (for messages and the docs' tables).
debian_root_release_name() {
  case "$1" in
    bookworm) echo "Debian 12" ;;
    trixie) echo "Debian 13" ;;
    *) echo "Debian $1" ;;
  esac
}

debian_root_mount() {
  local root=$1 target
  target="$root/proc"
  mount -t proc proc "$target" || return 1
  debian_root_mounts+=("$target")
  for target in sys dev; do
    mount --rbind "/$target" "$root/$target" && mount --make-rslave "$root/$target" || return 1
    debian_root_mounts+=("$root/$target")
  done
  cp /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true
  # mmdebstrap writes no /etc/hosts; an installed Debian has one (localhost, and its host name on
  # 127.0.1.1): without them Selenium cannot reach chromedriver and munge cannot find its origin.
  [ -e "$root/etc/hosts" ] ||
    printf '127.0.0.1\tlocalhost\n127.0.1.1\t%s\n::1\t\tlocalhost ip6-localhost ip6-loopback\n' \
      "$(cat "$root/etc/hostname" 2>/dev/null || hostname)" >"$root/etc/hosts"
}

debian_root_run() {
  local root=$1 command=$2
  chroot "$root" /usr/bin/env -i HOME=/root LANG=C.UTF-8 \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin /bin/bash -c "$command"
}

debian_root_release() {
  local root=$1 dir=$2 i
  # Reverse order; lazily if busy, so no bind mount of the host stays inside.
  for ((i = ${#debian_root_mounts[@]} - 1; i >= 0; i--)); do
    umount -R "${debian_root_mounts[i]}" 2>/dev/null || umount -R -l "${debian_root_mounts[i]}" ||
      echo "debian_root: could not unmount ${debian_root_mounts[i]}" >&2
  done
  debian_root_mounts=()
  if grep -q " $root/" /proc/self/mounts; then
    echo "debian_root: mounts remain under $root; not deleting $dir (remove them by hand)" >&2
    return 1
  fi
  if [ "${DEBIAN_ROOT_KEEP:-0}" = 1 ]; then
    echo "debian_root: kept $root" >&2
  else
    rm -rf --one-file-system "$dir"
  fi
}
