// Keeps two defects of the reference compiler out of our test results.
//
// 1. It is built with assertions, and a few programs make one fail (e.g. a
//    tuple holding a variable used as an array index, `a[[b]]`): glibc's
//    __assert_fail would abort the whole test program. While the oracle runs
//    the reference, a failed assertion becomes an exception that the oracle
//    turns into a result; anywhere else it aborts as glibc's does.
//    This file must not include <assert.h>: there __assert_fail is declared
//    noexcept, and an exception could not leave it.
// 2. It leaks syntax-tree nodes on some paths (seen in
//    Aseba::ImmediateNode::expandVectorialNodes and the shallowCopy methods),
//    which LeakSanitizer reports at exit in the sanitizer build. Leaks whose
//    allocation stack passes through the reference (namespace `Aseba`,
//    capitalised; ours is `aseba`) are suppressed, and only those.

#include "reference_containment.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace reference
{

namespace
{
thread_local bool reference_running = false;
} // namespace

ReferenceScope::ReferenceScope()
{
    reference_running = true;
}

ReferenceScope::~ReferenceScope()
{
    reference_running = false;
}

} // namespace reference

// Read by LeakSanitizer at start-up in sanitizer builds; unused otherwise.
extern "C" __attribute__((used)) const char *__lsan_default_suppressions()
{
    return "leak:Aseba::\n";
}

// Replaces glibc's definition for this program (static linking lets the
// program's own definition win).
extern "C" [[noreturn]] void __assert_fail(const char *assertion,
                                           const char *file,
                                           unsigned int line,
                                           const char *function)
{
    if (reference::reference_running)
        throw reference::ReferenceAssertion(std::string(file) + ":" + std::to_string(line) + ": " +
                                            function + ": assertion `" + assertion + "' failed");
    std::fprintf(stderr, "%s:%u: %s: Assertion `%s' failed.\n", file, line, function, assertion);
    std::abort();
}
