#!/usr/bin/env bash
# Runs every test program given, several at a time, prints a line per
# program as it finishes ([done/total], its counts, its time), and ends with
# one line: "N passed, N failed".
#
# A test program is a GoogleTest binary, or any other program (a script of
# browser tests, say) whose output ends with its own "N passed, N failed"
# line. One that crashes or prints no summary counts as one failure, and one
# that exits with a failure status while reporting none failed counts one
# more, so nothing can pass by not running. The output of a program with a
# failure is shown whole.
#
# Usage: scripts/run-tests.sh PROGRAM...
#   TEST_JOBS   programs run at once (default: the number of processors
#               and one more: many programs spend most of their time
#               waiting for the tools they drive, interop_test 3 s of
#               processor time in 23 s)
set -uo pipefail

jobs=${TEST_JOBS:-$(($(nproc 2>/dev/null || echo 2) + 1))}
total=$#
logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT

passed=0
failed=0
done_count=0
declare -A name_of=() start_of=() log_of=()

# GoogleTest binaries get brief, colourless output; other programs run as
# they are.
is_gtest() { [ "$(head -c 2 "$1")" != "#!" ] && grep -qa -- "gtest_brief" "$1"; }

start() { # program
    local test=$1 log
    log="$logs/$(basename "$test").$RANDOM.log"
    if is_gtest "$test"; then
        "$test" --gtest_color=no --gtest_brief=1 >"$log" 2>&1 &
    else
        "$test" >"$log" 2>&1 &
    fi
    name_of[$!]=$(basename "$test")
    start_of[$!]=$SECONDS
    log_of[$!]=$log
}

# Counts the finished program's tests; prints its line (and its output when
# something failed).
finish() { # pid status
    local pid=$1 status=$2 name=${name_of[$1]} log=${log_of[$1]} ran good bad summary
    done_count=$((done_count + 1))
    ran=$(sed -n 's/^\[==========\] \([0-9]*\) tests\? from .* ran\..*/\1/p' "$log" | tail -n1)
    if [ -n "$ran" ]; then
        good=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) tests\?\..*/\1/p' "$log" | tail -n1)
        # gtest's brief mode lists no failures: they are the tests that ran
        # and did not pass.
        good=${good:-0}
        bad=$((ran - good))
    else
        summary=$(grep -v '^[[:space:]]*$' "$log" | tail -n1)
        if [[ $summary =~ ^([0-9]+)\ passed,\ ([0-9]+)\ failed$ ]]; then
            good=${BASH_REMATCH[1]}
            bad=${BASH_REMATCH[2]}
        fi
    fi
    local seconds=$((SECONDS - ${start_of[$pid]}))
    if [ -z "${good:-}" ]; then
        tail -n 30 "$log"
        echo "[$done_count/$total] $name: no test summary (exit status $status), ${seconds} s"
        failed=$((failed + 1))
    else
        passed=$((passed + good))
        failed=$((failed + bad))
        if [ "$status" -ne 0 ] || [ "$bad" -ne 0 ]; then
            cat "$log"
            [ "$bad" -ne 0 ] || failed=$((failed + 1))
        fi
        echo "[$done_count/$total] $name: $good passed, $bad failed, ${seconds} s"
    fi
    unset "name_of[$pid]" "start_of[$pid]" "log_of[$pid]"
}

wait_for_one() {
    local pid status
    wait -n -p pid
    status=$?
    finish "$pid" "$status"
}

echo "running $total test programs, $jobs at a time"
for test in "$@"; do
    while [ ${#name_of[@]} -ge "$jobs" ]; do
        wait_for_one
    done
    start "$test"
done
while [ ${#name_of[@]} -gt 0 ]; do
    wait_for_one
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
