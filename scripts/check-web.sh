#!/usr/bin/env bash
# The IDE page's JavaScript (tools/ide/web/src), with the packages of its
# lockfile: ESLint (eslint.config.js), Prettier's format (.prettierrc.json)
# and TypeScript's check of the code and its JSDoc types (jsconfig.json).
# Ends with "N passed, N failed", one per check, so that `make test` runs it
# beside the test programs; the output of a failed check is shown whole.
# Usage: scripts/check-web.sh        (after npm ci in tools/ide/web; make test does it)
set -uo pipefail
cd "$(dirname "$0")/../tools/ide/web"

passed=0
failed=0
log=$(mktemp)
trap 'rm -f "$log"' EXIT
for check in lint format:check typecheck; do
    if npm run --silent "$check" >"$log" 2>&1; then
        passed=$((passed + 1))
    else
        failed=$((failed + 1))
        echo "check-web: npm run $check failed in tools/ide/web:"
        cat "$log"
    fi
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
