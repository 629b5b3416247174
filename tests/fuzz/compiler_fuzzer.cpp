// libFuzzer target for the compiler (tools/compiler): arbitrary text compiled
// as a script for both presets (our e-puck and the reference's dummy node),
// and read as an .aesl project whose every node program is then compiled for
// both. It stops on any
// sanitizer report, on an exception (compile and read_aesl promise none), or
// on a result that breaks the compiler's promises: bytecode that does not fit
// the target, or a line table that does not cover every word.
//
// Input: the text itself, so that scripts and projects seed the corpus as
// they are (scripts/fuzz.sh gives it examples/ and tests/compiler/programs/).
//
// Built and run by `make fuzz` (scripts/fuzz.sh).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string_view>

#include "tools/compiler/aesl.hpp"
#include "tools/compiler/compiler.hpp"
#include "tools/compiler/target_presets.hpp"

namespace
{

[[noreturn]] void fail(const char *why)
{
    std::fprintf(stderr, "compiler_fuzzer: %s\n", why);
    __builtin_trap();
}

const aseba::TargetDescription &epuck()
{
    static const aseba::TargetDescription target = aseba::epuck_target();
    return target;
}

const aseba::TargetDescription &dummy()
{
    static const aseba::TargetDescription target = aseba::dummy_target();
    return target;
}

// A project's definitions for scripts, so that `emit`, `onevent` and
// constants have something to find.
const aseba::CommonDefinitions &script_definitions()
{
    static const aseba::CommonDefinitions definitions = [] {
        aseba::CommonDefinitions made;
        made.events = { { "ping", 0 }, { "pair", 2 }, { "bad", 1 } };
        made.constants = { { "LIMIT", 100 }, { "NEGATIVE", -7 } };
        return made;
    }();
    return definitions;
}

void compile_and_check(std::string_view source,
                       const aseba::TargetDescription &target,
                       const aseba::CommonDefinitions &definitions)
{
    aseba::CompileResult result = aseba::compile(source, target, definitions);
    if (!result.ok)
        return;
    if (result.bytecode.size() > target.bytecode_size)
        fail("bytecode larger than the target's");
    if (result.line_of_word.size() != result.bytecode.size())
        fail("line table and bytecode differ in size");
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    std::string_view text(reinterpret_cast<const char *>(data), size);
    try {
        compile_and_check(text, epuck(), script_definitions());
        compile_and_check(text, dummy(), script_definitions());
        aseba::AeslReadResult project = aseba::read_aesl(text);
        if (!project.ok)
            return 0;
        for (const aseba::AeslNode &node : project.project.nodes) {
            compile_and_check(node.source, epuck(), project.project.definitions);
            compile_and_check(node.source, dummy(), project.project.definitions);
        }
    } catch (...) {
        fail("an exception escaped");
    }
    return 0;
}
