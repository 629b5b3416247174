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

} // namespace compiler_tests
