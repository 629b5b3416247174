// The reference compiler as a process of its own, for the whole-process
// figure of bench-compiler: Debian ships no compiler command (Studio and the
// other tools link libasebacompiler), so this is the least such a command
// does: read a script, compile it for the e-puck with the global event of
// the paper's annex (`bad`, one argument), and say whether it compiled.
//
//   bench-reference-compile FILE     exit status 0 when FILE compiles

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/compiler/reference_oracle.hpp"
#include "tools/compiler/target_presets.hpp"

int main(int argc, char **argv)
try {
    if (argc != 2) {
        std::fprintf(stderr, "usage: bench-reference-compile FILE\n");
        return 2;
    }
    std::ifstream file(argv[1], std::ios::binary);
    if (!file) {
        std::fprintf(stderr, "bench-reference-compile: cannot read %s\n", argv[1]);
        return 1;
    }
    std::string source(std::istreambuf_iterator<char>(file), {});
    aseba::CommonDefinitions definitions;
    definitions.events.push_back({ "bad", 1 });
    reference::ReferenceResult result =
      reference::compile_with_reference(source, aseba::epuck_target(), definitions);
    if (!result.ok) {
        std::fprintf(stderr, "%s: %s\n", argv[1], reference::describe(result).c_str());
        return 1;
    }
    return 0;
} catch (const std::exception &error) {
    std::fprintf(stderr, "bench-reference-compile: %s\n", error.what());
    return 1;
}
