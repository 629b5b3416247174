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
        Compilation compilation(target, definitions);
        std::vector<Token> tokens = tokenize(source);
        NodePointer program = parse_program(tokens, compilation);
        check_sizes(*program);
        expand_program(*program, compilation);
        check_types(*program, compilation);
        program = optimize(std::move(program));
        std::vector<Section> sections = generate_code(*program, compilation);
        check_stack(sections, compilation);
        link(std::move(sections), compilation, result);
        result.variables = compilation.variables;
        result.allocated_variables = static_cast<uint16_t>(compilation.next_free_address);
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
