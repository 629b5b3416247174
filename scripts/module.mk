# Checks of the sources themselves, run by `make test` beside the test
# programs (each ends with "N passed, N failed"):
#   check-layers.py   no firmware file includes a file of a higher layer
#   check-format.sh   every C and C++ file is formatted as .clang-format says
TEST_SCRIPTS += scripts/check-layers.py scripts/check-format.sh
