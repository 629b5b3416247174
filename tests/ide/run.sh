#!/usr/bin/env bash
# The IDE's browser tests: Debian's Chromium, headless, driven by
# playwright-core, on the page that aseba-ide serves, against simulated
# e-pucks (tests/ide/*.test.mjs: ide.test.mjs the whole page, the others one
# concern each), and the page's pure parts without a browser
# (tests/ide/page-units.test.mjs). Ends with "N passed, N failed".
#
# Usage: tests/ide/run.sh [--screenshots] [BIN_DIR]
#   BIN_DIR        where aseba-ide, epuck-emu and aseba are (default build/host/bin)
#   --screenshots  also take the documentation's pictures, docs/ide-*.png
set -uo pipefail
cd "$(dirname "$0")/../.."

screenshots=false
if [ "${1:-}" = --screenshots ]; then
    screenshots=true
    shift
fi
export BIN=${1:-build/host/bin}

passed=0
failed=0
log=$(mktemp)
trap 'rm -f "$log"' EXIT

# node's test runner prints its counts as "ℹ pass N" and "ℹ fail N".
# Every tests/ide/*.test.mjs, one file after another (each starts its own
# robots and server).
timeout 900 node --test --test-concurrency=1 --test-reporter=spec tests/ide/*.test.mjs 2>&1 | tee "$log"
status=${PIPESTATUS[0]}
good=$(sed -n 's/^ℹ pass \([0-9]*\)$/\1/p' "$log" | tail -n1)
bad=$(sed -n 's/^ℹ fail \([0-9]*\)$/\1/p' "$log" | tail -n1)
cancelled=$(sed -n 's/^ℹ cancelled \([0-9]*\)$/\1/p' "$log" | tail -n1)
if [ -z "$good" ]; then
    echo "tests/ide: no test summary (exit status $status)"
    failed=$((failed + 1))
else
    passed=$((passed + good))
    failed=$((failed + bad + ${cancelled:-0}))
    [ "$status" -eq 0 ] || [ "$bad" -ne 0 ] || failed=$((failed + 1))
fi

if $screenshots; then
    timeout 300 node tests/ide/screenshots.mjs docs 2>&1 | tee "$log"
    summary=$(tail -n1 "$log")
    if [[ $summary =~ ^([0-9]+)\ passed,\ ([0-9]+)\ failed$ ]]; then
        passed=$((passed + BASH_REMATCH[1]))
        failed=$((failed + BASH_REMATCH[2]))
    else
        echo "screenshots.mjs: no summary"
        failed=$((failed + 1))
    fi
fi

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
