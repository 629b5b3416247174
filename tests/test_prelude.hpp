// What every test file of the sanitized build includes first, precompiled
// once (Makefile: TEST_PRELUDE): GoogleTest's header, which each test file
// would otherwise parse again (a fifth of its compile).
#include <gtest/gtest.h>
