#!/usr/bin/env bash
# Runs every test program given and ends with one line: "N passed, N failed".
# Test programs are GoogleTest binaries; one that crashes or prints no
# summary counts as one failure, so nothing can pass by not running.
set -uo pipefail

passed=0
failed=0
for test in "$@"; do
    name=$(basename "$test")
    log=$(mktemp)
    "$test" --gtest_color=no --gtest_brief=1 >"$log" 2>&1
    status=$?
    ran=$(sed -n 's/^\[==========\] \([0-9]*\) tests\? from .* ran\..*/\1/p' "$log" | tail -n1)
    good=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) tests\?\..*/\1/p' "$log" | tail -n1)
    if [ -z "$ran" ]; then
        echo "$name: no test summary (exit status $status)"
        tail -n 30 "$log"
        failed=$((failed + 1))
    else
        # gtest's brief mode lists no failures: they are the tests that ran
        # and did not pass.
        bad=$((ran - ${good:-0}))
        passed=$((passed + ran - bad))
        failed=$((failed + bad))
        if [ "$status" -ne 0 ] || [ "$bad" -ne 0 ]; then
            cat "$log"
            [ "$bad" -ne 0 ] || failed=$((failed + 1))
        fi
        echo "$name: $((ran - bad)) passed, $bad failed"
    fi
    rm -f "$log"
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
