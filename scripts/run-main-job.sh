#!/usr/bin/env bash
# The main job, on its built-in default: the paper's arena (a square with
# red, green and blue ground areas; the experimenter knocks robots that
# linger on red) with six simulated e-pucks in it, each running the real
# firmware with the 2007 paper's swarm controller, as one Aseba network on
# TCP port 33333 that Aseba Studio, the console and the Debian tools can
# join. Paced to real time; stop it with Ctrl-C.
# Usage: run-main-job.sh BUILD_HOST_DIR [epuck-emu options...]
set -euo pipefail
bin=$1/bin
shift
echo "Six e-pucks in the default arena running examples/paper-annex.aesl; join with e.g."
echo "  asebastudio 'tcp:localhost;33333'   or   $bin/aseba nodes"
echo "Alarms: 'bad N (colour:count ...)', colours 0 red, 1 green, 2 blue."
exec "$bin/epuck-emu" --arena default --speed realtime --port 33333 \
    --load examples/paper-annex.aesl "$@"
