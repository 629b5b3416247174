#!/usr/bin/env bash
# Runs an STM32F4 image (`make stm32f4`) on QEMU's netduinoplus2 board (an
# STM32F405), its USART1 a TCP server on the loopback interface: the Aseba
# node that tools reach at tcp:127.0.0.1;PORT, one client at a time.
#
# Usage: scripts/qemu-node.sh [--port PORT] [--icount] [--wait] [IMAGE.elf]
#   --port PORT  the TCP port (default: a free one)
#   --icount     deterministic time: the guest's clock counts instructions,
#                one per nanosecond (-icount shift=0), for measurements
#   --wait       start the board when the first client connects (nothing it
#                sends at boot is lost); by default it starts at once, and
#                bytes that arrive before its USART is on are dropped
#   IMAGE.elf    default: build/stm32f4/epuck-aseba-stm32f4.elf
#
# Prints "qemu-node: tcp:127.0.0.1;PORT" on stderr, then becomes QEMU (exec),
# so the script's PID is QEMU's: stop it with kill. QEMU's own messages go to
# stderr; the board has no screen and no monitor.
set -euo pipefail

port=
icount=()
wait=off
image=build/stm32f4/epuck-aseba-stm32f4.elf
while [ $# -gt 0 ]; do
    case $1 in
    --port) port=$2; shift 2 ;;
    --icount) icount=(-icount shift=0,sleep=off); shift ;;
    --wait) wait=on; shift ;;
    -h | --help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "qemu-node: unknown option $1 (see --help)" >&2; exit 2 ;;
    *) image=$1; shift ;;
    esac
done
[ -f "$image" ] || { echo "qemu-node: no image $image (make stm32f4 builds it)" >&2; exit 2; }
command -v qemu-system-arm >/dev/null ||
    { echo "qemu-node: qemu-system-arm is missing (scripts/install-deps.sh installs it)" >&2; exit 2; }
if [ -z "$port" ]; then
    port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
fi

echo "qemu-node: tcp:127.0.0.1;$port" >&2
# nodelay: QEMU writes a byte at a time, and Nagle's algorithm with delayed
# acknowledgements would make a round trip take some 40 ms instead of half a
# millisecond; the server takes one client at a time, the next once it leaves.
exec qemu-system-arm -M netduinoplus2 -display none -monitor none \
    -serial "tcp:127.0.0.1:$port,server=on,wait=$wait,nodelay=on" "${icount[@]}" -kernel "$image"
