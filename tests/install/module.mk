# What each make target installs (a script test, "N passed, N failed").
TEST_SCRIPTS += tests/install/install_groups_test.py
