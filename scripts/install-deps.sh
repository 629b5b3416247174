#!/usr/bin/env bash
# Installs the Debian packages the project needs, and nothing when they are
# all present. Used by `make` and by CI; safe to run again at any time.
set -euo pipefail

packages=(
    make g++ gcc                                   # host build
    libgtest-dev                                   # tests
    clang libclang-rt-14-dev                       # fuzzing (libFuzzer) and sanitizers
    gcc-avr avr-libc binutils-avr                  # cross-check: 16-bit int
    gcc-arm-none-eabi libnewlib-arm-none-eabi      # cross-check: Cortex-M; make stm32f4
    qemu-system-arm                                # the STM32F4 image's tests (QEMU netduinoplus2)
    simavr libsimavr-dev                           # benchmarks: the VM on an AVR
    aseba libdashel-dev locales                    # the reference implementation (tests only)
    valgrind                                       # instruction counts in benchmarks
    python3                                        # test and benchmark scripts
    libenki-dev                                    # the simulated arena (physics, e-puck sensors)
    libasio-dev libwebsocketpp-dev                 # the IDE's server (HTTP and WebSocket)
    nlohmann-json3-dev libcli11-dev libpugixml-dev # JSON, command lines, .aesl projects
    nodejs                                         # the IDE's page: npm and esbuild build it
    chromium                                       # the IDE's browser tests (driven by npm playwright-core)
)

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
if ! locale -a 2>/dev/null | grep -qi '^en_US\.utf-\?8$'; then
    echo "install-deps: generating the en_US.UTF-8 locale"
    as_root localedef -i en_US -f UTF-8 en_US.UTF-8
fi
