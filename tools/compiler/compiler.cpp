// The compilation pipeline of language.md §9, from text to linked bytecode.

#include "compiler.hpp"

#include "codegen.hpp"
#include "compilation.hpp"
#include "diagnostics.hpp"
#include "lexer.hpp"

namespace aseba
{

CompileResult compile(std::string_view source,
                      const TargetDescription &target,
                      const CommonDefinitions &definitions)
{
    CompileResult result;
    try {
        if (source.size() > MAX_SOURCE_BYTES)
            throw CompileFailure("This program is " + std::to_string(source.size()) +
                                 " bytes long; the compiler takes at most " +
                                 std::to_string(MAX_SOURCE_BYTES) + " bytes (1 MiB)");
        if (std::string limits = target_limits_error(target); !limits.empty())
            throw CompileFailure("Broken target description: " + limits);
        Compilation compilation(target, definitions);
        std::vector<Token> tokens = tokenize(source);
        NodePointer program = parse_program(tokens, compilation);
        allocate_locals(*program, compilation);
        check_sizes(*program);
        expand_program(*program, compilation);
        check_types(*program, compilation);
        check_memory(compilation);
        program = optimize(std::move(program));
        std::vector<Section> sections = generate_code(*program, compilation);
        check_stack(sections, compilation);
        link(std::move(sections), compilation, result);
        result.variables = compilation.variables;
        for (const LocalVariable &local : compilation.locals)
            result.locals.push_back(
              { local.name,
                compilation.frames[local.frame].title,
                static_cast<uint16_t>(compilation.local_address(local.frame, local.offset)),
                static_cast<uint16_t>(local.size) });
        result.locals_words = static_cast<uint16_t>(compilation.locals_size);
        result.allocated_variables =
          static_cast<uint16_t>(compilation.locals_start + compilation.locals_size);
        result.ok = true;
    } catch (const CompileFailure &failure) {
        result = CompileResult{};
        result.error = failure.error;
    } catch (const std::exception &exception) {
        result = CompileResult{};
        result.error.message = std::string("Internal compiler error: ") + exception.what();
    }
    return result;
}

} // namespace aseba
