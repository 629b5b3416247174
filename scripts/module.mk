# Checks of the sources themselves, run by `make test` beside the test
# programs (each ends with "N passed, N failed"):
#   check-layers.py   no firmware file includes a file of a higher layer
#   check-format.sh   every C and C++ file is formatted as .clang-format says
#   check-web.sh      the IDE page's JavaScript: ESLint, Prettier, TypeScript
#                     (with the packages of tools/ide/web's lockfile, which
#                     tools/ide/module.mk installs)
TEST_SCRIPTS += scripts/check-layers.py scripts/check-format.sh scripts/check-web.sh
scripts/check-web.sh: | tools/ide/web/node_modules/.package-lock.json
