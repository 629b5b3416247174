#!/usr/bin/env bash
# Runs a command in a fresh Debian 12 system, as on a user's new machine:
# a minimal root made by debootstrap from Debian's packages, holding only
# this checkout's files (the ones git knows, as they are in the work tree)
# and ../shared beside it, and nothing that earlier work installed. CI runs
# the README's commands this way, so that a missing install step fails
# there as it would on a user's machine.
#
# Usage (as root): scripts/fresh-machine.sh COMMAND...
#   e.g. scripts/fresh-machine.sh 'make run RUN_ARGS="--duration 10" && make test'
#
# The command runs in bash, in the checkout's copy, after the README's
# first step (`apt-get install git make`). The base system is made once and
# kept as a tarball in $FRESH_MACHINE_CACHE (default
# /var/cache/epuck-aseba-fresh-machine); the machine's own apt cache is
# lent to the root so that packages already downloaded are not fetched
# again. Everything else is thrown away when the command ends.
set -euo pipefail
[ "$(id -u)" = 0 ] || { echo "fresh-machine: run as root (chroot, mount)" >&2; exit 2; }
[ $# -gt 0 ] || { echo "usage: scripts/fresh-machine.sh COMMAND..." >&2; exit 2; }

checkout=$(cd "$(dirname "$0")/.." && pwd)
shared=$(cd "$checkout/../shared" 2>/dev/null && pwd || true)
cache=${FRESH_MACHINE_CACHE:-/var/cache/epuck-aseba-fresh-machine}
mirror=${FRESH_MACHINE_MIRROR:-http://deb.debian.org/debian}
base=$cache/bookworm-minbase.tar
root=$(mktemp -d /var/tmp/epuck-aseba-fresh-machine.XXXXXX)
mounted=()

# Unmounts what was mounted, innermost first, and only then removes the
# root: never remove a tree with the machine's /dev bound inside it.
cleanup() {
    local i process
    # What still runs in the root (the command was interrupted) goes first.
    for process in /proc/[0-9]*; do
        [ "$(readlink "$process/root" 2>/dev/null)" = "$root" ] && kill -9 "${process#/proc/}" 2>/dev/null
    done
    for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do
        umount -l "${mounted[i]}" 2>/dev/null || true
    done
    if ! grep -q " $root" /proc/mounts; then
        rm -rf --one-file-system "$root"
    else
        echo "fresh-machine: $root is still mounted; left in place" >&2
    fi
}
trap cleanup EXIT

bind() { # source target [mount options...]
    mkdir -p "$root$2"
    mount "${@:3}" "$1" "$root$2"
    mounted+=("$root$2")
}

if [ ! -f "$base" ]; then
    echo "fresh-machine: making a minimal Debian 12 root (once; kept in $cache)"
    command -v debootstrap >/dev/null || {
        apt-get update -q && apt-get install -y -q --no-install-recommends debootstrap; }
    mkdir -p "$cache" "$root/base"
    debootstrap --variant=minbase bookworm "$root/base" "$mirror" >"$root/debootstrap.log" 2>&1 ||
        { tail -20 "$root/debootstrap.log" >&2; exit 1; }
    tar -C "$root/base" -cf "$base.partial" . && mv "$base.partial" "$base"
    rm -rf --one-file-system "$root/base" "$root/debootstrap.log"
fi
tar -C "$root" -xf "$base"

# The checkout as git knows it, in the user's home, and ../shared beside
# it, read-only as CI has it.
place=/root/src
mkdir -p "$root$place/epuck-aseba"
git -C "$checkout" ls-files -z --cached --others --exclude-standard |
    (cd "$checkout" && tar --null -T - -cf -) | tar -C "$root$place/epuck-aseba" -xf -
if [ -n "$shared" ]; then
    cp -a "$shared" "$root$place/shared"
    chmod -R a-w "$root$place/shared"
fi

# The machine's network, as a user's machine has its own: its resolver, its
# extra certificate authorities (a TLS proxy's, say) and the variables that
# point programs at them or at a proxy. These are settings, not packages.
cp /etc/resolv.conf "$root/etc/resolv.conf"
# debootstrap writes no hosts file; every installed Debian has one that
# names localhost (the installer writes it), and our tests connect there.
printf '127.0.0.1\tlocalhost\n::1\t\tlocalhost ip6-localhost ip6-loopback\n' >"$root/etc/hosts"
if [ -d /usr/local/share/ca-certificates ]; then
    mkdir -p "$root/usr/local/share/ca-certificates"
    cp -a /usr/local/share/ca-certificates/. "$root/usr/local/share/ca-certificates/"
fi
network_settings=()
for name in http_proxy https_proxy no_proxy HTTP_PROXY HTTPS_PROXY NO_PROXY NODE_EXTRA_CA_CERTS \
    SSL_CERT_FILE SSL_CERT_DIR REQUESTS_CA_BUNDLE CURL_CA_BUNDLE PIP_CERT GIT_SSL_CAINFO; do
    [ -z "${!name:-}" ] || network_settings+=("$name=${!name}")
done
bind proc /proc -t proc
bind sysfs /sys -t sysfs
bind /dev /dev --bind
bind devpts /dev/pts -t devpts
bind tmpfs /dev/shm -t tmpfs
bind /var/cache/apt/archives /var/cache/apt/archives --bind

echo "fresh-machine: running in a fresh Debian 12: $*"
chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    LANG=C.UTF-8 CI="${CI:-}" DEBIAN_FRONTEND=noninteractive "${network_settings[@]}" \
    bash -c 'set -euo pipefail
             cd '"$place"'/epuck-aseba
             apt-get update -q >/dev/null
             apt-get install -y -q --no-install-recommends git make >/dev/null
             '"$*"
