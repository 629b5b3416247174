#!/usr/bin/env bash
# Checks that every C and C++ file of the project is formatted as
# .clang-format says (clang-format --dry-run --Werror), and prints the
# differences of those that are not. Ends with "N passed, N failed", one
# per file, so that `make test` runs it beside the test programs.
# Usage: scripts/check-format.sh            the check
#        scripts/check-format.sh --apply    formats them instead (`make format`)
set -uo pipefail
cd "$(dirname "$0")/.."

# The project's files, whether git is there or not (CI's fresh system has
# the files only): the build's outputs and npm's packages are not ours.
mapfile -t files < <(find . \( -path ./build -o -path ./.git -o -name node_modules \) -prune -o \
                          -type f \( -name '*.c' -o -name '*.h' -o -name '*.cpp' -o -name '*.hpp' \) \
                          -print | sed 's|^\./||' | sort)

if [ "${1:-}" = --apply ]; then
    clang-format -i "${files[@]}"
    echo "check-format: formatted ${#files[@]} files"
    exit 0
fi

# One clang-format for every file (it names those it would change), then
# the differences of each of those.
mapfile -t unformatted < <(clang-format --dry-run "${files[@]}" 2>&1 |
                               sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: \(warning\|error\): .*clang-format.*/\1/p' |
                               sort -u)
for file in "${unformatted[@]}"; do
    echo "check-format: $file is not formatted as .clang-format says (make format):"
    clang-format "$file" | diff -u "$file" - | head -n 20
done
echo "$((${#files[@]} - ${#unformatted[@]})) passed, ${#unformatted[@]} failed"
[ "${#unformatted[@]}" -eq 0 ]
