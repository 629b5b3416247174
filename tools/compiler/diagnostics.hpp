// The one way the compiler stops: a CompileFailure carrying the first error,
// thrown by any phase and turned into a CompileResult by compile().

#pragma once

#include <stdexcept>
#include <string>

#include "compiler.hpp"

namespace aseba
{

class CompileFailure : public std::runtime_error
{
  public:
    CompileFailure(SourcePosition position, const std::string &message)
      : std::runtime_error(message)
      , error{ true, position, message }
    {
    }
    explicit CompileFailure(const std::string &message)
      : std::runtime_error(message)
      , error{ false, {}, message }
    {
    }
    CompileError error;
};

// Throws the error at `position`.
[[noreturn]] inline void fail(SourcePosition position, const std::string &message)
{
    throw CompileFailure(position, message);
}

// The size error of language.md §6, at `position`.
[[noreturn]] inline void fail_size(SourcePosition position, unsigned left, unsigned right)
{
    fail(position,
         "Size error! Size of array1 = " + std::to_string(left) +
           " ; size of array2 = " + std::to_string(right));
}

} // namespace aseba
