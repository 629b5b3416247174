# The documentation's references: every file that the user's docs and the
# programs' help texts name exists in the repository (a script test: it
# ends with "N passed, N failed", run from the repository's root).
TEST_SCRIPTS += tests/docs/references_test.py
