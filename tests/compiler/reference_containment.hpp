// Failed assertions inside the reference compiler, as exceptions: see
// reference_containment.cpp for why and how narrowly.

#pragma once

#include <stdexcept>

namespace reference
{

// Thrown instead of aborting when the reference compiler fails an assertion.
struct ReferenceAssertion : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// While one exists on this thread, failed assertions throw ReferenceAssertion.
class ReferenceScope
{
  public:
    ReferenceScope();
    ~ReferenceScope();
    ReferenceScope(const ReferenceScope &) = delete;
    ReferenceScope &operator=(const ReferenceScope &) = delete;
};

} // namespace reference
