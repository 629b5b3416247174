// Where our compiler's errors may differ from the reference's on purpose
// (docs/language.md, Errors): the tests that compare the two allow these
// differences and no others.

#pragma once

#include <string>

namespace compiler_tests
{

// Whether `ours` is the positioned form of the reference's positionless
// stack or size error `reference` (ours say where it happens).
bool is_positioned_version(const std::string &reference, const std::string &ours);

// Whether `ours` is the reference's message, or one of our rewordings of it
// (what was expected, named; a literal as written).
bool is_our_wording(const std::string &reference, const std::string &ours);

// Whether the reference stopped at an opening parenthesis after a name, where
// ours reads a call (docs/language.md): the two may then stop at different
// columns of the line, each with its own message.
bool reference_stopped_at_a_call(const std::string &reference);

// Whether `ours` is one of the errors found only once the whole program is
// read (stack, recursion, script size), which the reference reports last.
bool is_whole_program_error(const std::string &ours);

} // namespace compiler_tests
