#!/usr/bin/env bash
# Installs the Debian packages the project needs, and nothing when they are
# all present. Used by `make` and by CI; safe to run again at any time.
# Usage: scripts/install-deps.sh [GROUP...]      (default: build)
#
#   build  what `make` and `make run` need: compilers and the host tools'
#          libraries (a small install)
#   test   what `make test` adds: GoogleTest, and the reference Aseba that
#          the tests use as an oracle (its GUI dependencies make it large),
#          and whatever a test runs (QEMU, Chromium, mosquitto, matplotlib);
#          `make test` also takes the dspic30 group, for the e-puck's images
#   cross  the cross compilers of `make cross-check`
#   fuzz   clang and libFuzzer for `make fuzz`
#   bench  valgrind and the reference Aseba for `make bench`
#   experiment  matplotlib for the figure of `make experiment`
#   dspic30  what `make dspic30` needs without Microchip XC16: the libraries of
#          the GPL pic30-elf toolchain, which it then unpacks into
#          $BUILD/toolchains (BUILD, default build) from
#          ../shared/toolchains/pic30/ beside the checkout
set -euo pipefail
self=$(realpath "$0")
cd "$(dirname "$self")/.."
build=${BUILD:-build}

# One install at a time: make runs the groups of a target in parallel, and
# apt-get refuses to run twice at once. The script itself is the lock.
exec 9<"$self"
flock 9

declare -A groups=(
    [build]="make g++ gcc
             libpugixml-dev nlohmann-json3-dev libcli11-dev libasio-dev
             libenki-dev libwebsocketpp-dev nodejs libmosquitto-dev"
    [test]="libgtest-dev python3 aseba libdashel-dev locales
            qemu-system-arm gcc-arm-none-eabi libnewlib-arm-none-eabi chromium
            mosquitto python3-paho-mqtt python3-matplotlib clang-format"
    [cross]="gcc-avr avr-libc binutils-avr gcc-arm-none-eabi libnewlib-arm-none-eabi"
    [fuzz]="clang libclang-rt-14-dev libpugixml-dev nlohmann-json3-dev libasio-dev aseba"
    [bench]="chromium valgrind python3 aseba libdashel-dev locales gcc-avr avr-libc binutils-avr
             gcc-arm-none-eabi libnewlib-arm-none-eabi simavr libsimavr-dev qemu-system-arm
             mosquitto"
    [experiment]="python3 python3-matplotlib"
    [dspic30]="xz-utils libgmp10 zlib1g libexpat1 python3"
)
# What each package is for:
#   libpugixml-dev      .aesl projects (XML)
#   nlohmann-json3-dev  target descriptions (JSON)
#   libcli11-dev        every program's command line
#   libasio-dev         standalone asio: TCP, serial ports, timers
#   libenki-dev         the simulated arena (physics, e-puck sensors)
#   aseba, libdashel-dev, locales   the reference implementation, an oracle
#                                   for tests and benchmarks only
#   valgrind            instruction counts in benchmarks
#   clang-format        the format check of `make test` (scripts/check-format.sh)
#   libwebsocketpp-dev  the IDE's server: HTTP and WebSocket on asio
#   nodejs              the IDE's page: npm installs its lockfile, esbuild bundles it
#   chromium            the IDE's browser tests and benchmarks (headless, driven by
#                       playwright-core from the page's lockfile)
#   qemu-system-arm, gcc-arm-none-eabi   the STM32F4 image and its tests
#                       (QEMU netduinoplus2)
#   simavr              benchmarks: the VM on an AVR, as a proxy for the dsPIC
#   libmosquitto-dev    aseba-mqtt's MQTT client (docs/mqtt.md)
#   mosquitto, python3-paho-mqtt   the broker of its tests and benchmarks, and
#                       the client of its Python example (examples/mqtt)
#   libgmp10, zlib1g, libexpat1    what the pic30-elf compiler and binutils link

wanted=("$@")
[ ${#wanted[@]} -gt 0 ] || wanted=(build)

packages=()
for group in "${wanted[@]}"; do
    [ -n "${groups[$group]:-}" ] || { echo "install-deps: unknown group '$group'" >&2; exit 2; }
    # shellcheck disable=SC2206 # package names are words
    packages+=(${groups[$group]})
done

missing=()
for package in "${packages[@]}"; do
    status=$(dpkg-query -W -f='${db:Status-Status}' "$package" 2>/dev/null || true)
    [ "$status" = installed ] || missing+=("$package")
done

as_root() {
    if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi
}

if [ ${#missing[@]} -gt 0 ]; then
    echo "install-deps: installing ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    as_root apt-get update -q
    as_root apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# The reference compiler refuses to start without this locale.
if [[ " ${packages[*]} " == *" locales "* ]] &&
    ! locale -a 2>/dev/null | grep -qi '^en_US\.utf-\?8$'; then
    echo "install-deps: generating the en_US.UTF-8 locale"
    as_root localedef -i en_US -f UTF-8 en_US.UTF-8
fi

# Debian's own nodejs comes without npm (a build from nodejs.org or
# NodeSource includes it): the IDE's page needs it.
if [[ " ${packages[*]} " == *" nodejs "* ]] && ! command -v npm >/dev/null; then
    echo "install-deps: installing npm"
    export DEBIAN_FRONTEND=noninteractive
    as_root apt-get install -y -q --no-install-recommends npm
fi

# The GPL build of XC16's compiler and binutils, unpacked once.
if [[ " ${wanted[*]} " == *" dspic30 "* ]] && [ ! -x "$build/toolchains/pic30-elf/bin/pic30-elf-gcc" ]; then
    archives=(../shared/toolchains/pic30/pic30-elf-*.tar.xz)
    if [ ! -f "${archives[0]}" ]; then
        echo "install-deps: no dsPIC toolchain: ../shared/toolchains/pic30/pic30-elf-*.tar.xz is not beside" >&2
        echo "  this checkout. Install Microchip MPLAB XC16 (https://www.microchip.com/xc16) and run" >&2
        echo "  make dspic30 XC16_DIR=ITS/bin, or give DSPIC_TOOLCHAIN=DIR, a pic30-elf GCC toolchain." >&2
        exit 1
    fi
    echo "install-deps: unpacking ${archives[0]##*/} into $build/toolchains"
    mkdir -p "$build/toolchains"
    tar -xJf "${archives[0]}" -C "$build/toolchains"
fi
