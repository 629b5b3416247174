#!/usr/bin/env bash
# The main job, on its built-in default: the paper's arena (a square with
# red, green and blue ground areas; the experimenter knocks robots that
# linger on red) with six simulated e-pucks in it, each running the real
# firmware with the 2007 paper's swarm controller, as one Aseba network on
# TCP port 33333, and the group IDE on it at http://localhost:33380/ (the
# arena view fed on port 33334). Paced to real time; stop it with Ctrl-C.
# Usage: run-main-job.sh BUILD_HOST_DIR [epuck-emu options...]
set -euo pipefail
host=$1
bin=$host/bin
shift
network_port=33333
feed_port=33334
ide_port=${IDE_PORT:-33380}
# The IDE edits a copy of the controller, so that Save never changes the
# example; the copy is kept between runs.
project=$(dirname "$host")/run/paper-annex.aesl
mkdir -p "$(dirname "$project")"
[ -e "$project" ] || cp examples/paper-annex.aesl "$project"

# The robots start with the example: while the copy is the same, the IDE
# knows their programs from the start (variables and lines by name).
same_program=()
cmp -s "$project" examples/paper-annex.aesl && same_program=(--robots-run-project)

"$bin/aseba-ide" --port "$ide_port" --arena "localhost:$feed_port" --project "$project" \
    "${same_program[@]}" "tcp:localhost;$network_port" &
ide=$!
trap 'kill "$ide" 2>/dev/null || true; wait "$ide" 2>/dev/null || true' EXIT
sleep 0.3
kill -0 "$ide" 2>/dev/null || { echo "run: the IDE could not start (is port $ide_port in use? IDE_PORT=N picks another)"; exit 1; }

echo "Six e-pucks in the default arena running examples/paper-annex.aesl."
echo "  The group IDE:  http://localhost:$ide_port/   (open it in a browser; Save writes $project)"
echo "  Other tools:    asebastudio 'tcp:localhost;$network_port'   or   $bin/aseba nodes"
echo "Alarms: 'bad N (colour:count ...)', colours 0 red, 1 green, 2 blue. Ctrl-C stops."
"$bin/epuck-emu" --arena default --speed realtime --port "$network_port" --arena-feed "$feed_port" \
    --load examples/paper-annex.aesl "$@"
