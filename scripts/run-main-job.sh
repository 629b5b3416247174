#!/usr/bin/env bash
# The main job, on its built-in default: six simulated e-pucks, each running
# the real firmware with the 2007 paper's swarm controller, as one Aseba
# network on TCP port 33333 that Aseba Studio, the console and the Debian
# tools can join. Stop it with Ctrl-C.
#
# The robots stand in a flat, empty world (the Enki arena is to come): their
# drivers read neutral sensors and no camera, so the controller drives
# straight and raises no alarm.
# Usage: run-main-job.sh BUILD_HOST_DIR [epuck-emu options...]
set -euo pipefail
bin=$1/bin
shift
echo "Six e-pucks running examples/paper-annex.aesl; join with e.g."
echo "  asebastudio 'tcp:localhost;33333'   or   $bin/aseba nodes"
exec "$bin/epuck-emu" --robots 6 --port 33333 --load examples/paper-annex.aesl "$@"
