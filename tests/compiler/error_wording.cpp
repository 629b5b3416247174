// Our deliberate differences from the reference's error messages.

#include "error_wording.hpp"

namespace compiler_tests
{
namespace
{

bool starts_with(const std::string &text, const std::string &prefix)
{
    return text.rfind(prefix, 0) == 0;
}

} // namespace

bool is_positioned_version(const std::string &reference, const std::string &ours)
{
    if (starts_with(reference, "Execution stack will overflow"))
        return starts_with(ours, "Execution stack will overflow") ||
               starts_with(ours, "Recursion is not allowed");
    return starts_with(reference, "Script too big") && starts_with(ours, "Script too big");
}

bool is_our_wording(const std::string &reference, const std::string &ours)
{
    if (starts_with(reference, "Expecting "))
        return starts_with(ours, "Expecting ") &&
               ours.find("Expecting string") == std::string::npos;
    if (starts_with(reference, "Integer value "))
        return starts_with(ours, "Integer value ") && ours.find(" range") != std::string::npos;
    return reference == ours;
}

bool reference_stopped_at_a_call(const std::string &reference)
{
    return reference.find("( (open parenthesis) instead") != std::string::npos;
}

bool is_whole_program_error(const std::string &ours)
{
    return starts_with(ours, "Execution stack will overflow") ||
           starts_with(ours, "Recursion is not allowed") || starts_with(ours, "Script too big");
}

} // namespace compiler_tests
