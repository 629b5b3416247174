// For GoogleTest bodies that use the reference compiler: stops the test with
// a clear failure when the reference cannot run here (no en_US.UTF-8 locale).

#pragma once

#include <gtest/gtest.h>

#include <string>

#include "reference_oracle.hpp"

#define REQUIRE_REFERENCE()                                                                        \
    do {                                                                                           \
        std::string reference_unavailable;                                                         \
        ASSERT_TRUE(reference::reference_locale_available(&reference_unavailable))                 \
          << reference_unavailable;                                                                \
    } while (false)
