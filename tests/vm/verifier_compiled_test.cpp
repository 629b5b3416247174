// The verifier accepts every program that a compiler produces: ours and the
// reference (Debian's libasebacompiler), on the upstream corpus, on the
// hand-written programs of the compiler tests, on the examples and on
// generated programs for a roomy and a tight node. A compiled program the
// verifier refused would be a program users could no longer run.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/compiler/corpus.hpp"
#include "tests/compiler/program_generator.hpp"
#include "tests/compiler/reference_oracle.hpp"
#include "tests/compiler/require_reference.hpp"
#include "tests/compiler/test_targets.hpp"
#include "tools/compiler/compiler.hpp"
#include "tools/compiler/program_file.hpp"
#include "tools/compiler/target_presets.hpp"

extern "C" {
#include "robots/epuck/epuck_natives.h"
#include "nat_standard.h"
#include "vm.h"
}

namespace
{

using aseba::TargetDescription;

void ignore_emit(void *, uint16_t, const int16_t *, uint16_t) {}
void ignore_report(void *, uint16_t, const uint16_t *, uint16_t) {}
void ignore_error(void *, uint16_t, const char *) {}
const vm_callbacks quiet = { ignore_emit, ignore_report, ignore_error };

// The verifier's verdict on `bytecode` in a node of `target`'s sizes with
// `natives`: empty when accepted, else the fault and its place.
std::string verdict(const std::vector<uint16_t> &bytecode,
                    const TargetDescription &target,
                    const vm_native_table &natives)
{
    std::vector<uint16_t> memory(target.bytecode_size);
    std::vector<int16_t> variables(target.variables_size);
    std::vector<int16_t> stack(target.stack_size);
    vm_memory layout = { memory.data(),
                         target.bytecode_size,
                         variables.data(),
                         target.variables_size,
                         stack.data(),
                         target.stack_size,
                         0 };
    vm_state vm;
    vm_init(&vm, &layout, 1, &natives, &quiet, nullptr);
    vm_set_bytecode(&vm, 0, bytecode.data(), static_cast<uint16_t>(bytecode.size()));
    if (vm.rejection == nullptr)
        return "";
    return std::string(vm.rejection) + " at " + std::to_string(vm.rejection_pc);
}

// Compiles `source` with both compilers; each bytecode that results must be
// accepted. Returns how many were checked.
int check_both_compilers(const std::string &name,
                         const std::string &source,
                         const TargetDescription &target,
                         const aseba::CommonDefinitions &definitions,
                         const vm_native_table &natives)
{
    int checked = 0;
    const aseba::CompileResult ours = aseba::compile(source, target, definitions);
    if (ours.ok) {
        EXPECT_EQ(verdict(ours.bytecode, target, natives), "") << name << ", our compiler";
        checked++;
    }
    const reference::ReferenceResult theirs =
      reference::compile_with_reference(source, target, definitions);
    if (theirs.ok) {
        EXPECT_EQ(verdict(theirs.bytecode, target, natives), "") << name << ", reference";
        checked++;
    }
    return checked;
}

TEST(VerifierOnCompiledCode, AcceptsTheUpstreamCorpus)
{
    REQUIRE_REFERENCE();
    const TargetDescription target =
      compiler_tests::corpus_target(compiler_tests::standard_natives());
    int checked = 0;
    for (const compiler_tests::CorpusCase &row : compiler_tests::read_corpus_manifest())
        checked += check_both_compilers(row.script,
                                        compiler_tests::read_corpus_file(row.script),
                                        target,
                                        compiler_tests::corpus_definitions(),
                                        nat_standard_table);
    EXPECT_GT(checked, 100);
}

TEST(VerifierOnCompiledCode, AcceptsTheHandWrittenProgramsAndTheExamples)
{
    REQUIRE_REFERENCE();
    int checked = 0;
    // For the e-puck, as the firmware would get them: the hand-written
    // programs use its sensors and actuators, and these events and constant
    // (those tests/compiler/differential_test.cpp gives them).
    const TargetDescription epuck = aseba::epuck_target();
    aseba::CommonDefinitions definitions;
    definitions.events = { { "bad", 1 }, { "alarm", 2 }, { "ping", 1 }, { "status", 4 } };
    definitions.constants = { { "LIMIT", 5 } };
    for (const auto &entry : std::filesystem::directory_iterator("tests/compiler/programs")) {
        if (entry.path().extension() != ".aseba")
            continue;
        std::ifstream file(entry.path(), std::ios::binary);
        std::ostringstream source;
        source << file.rdbuf();
        checked += check_both_compilers(
          entry.path().string(), source.str(), epuck, definitions, epuck_native_table);
    }
    for (const char *path : { "examples/paper-annex.aesl", "examples/sound-direction.aesl" }) {
        aseba::ProgramFile program = aseba::read_program_file(path);
        std::string error;
        aseba::CompileResult result = aseba::compile_program_file(program, epuck, error);
        ASSERT_TRUE(result.ok) << path << ": " << error;
        EXPECT_EQ(verdict(result.bytecode, epuck, epuck_native_table), "") << path;
        checked++;
    }
    EXPECT_EQ(checked, 14) << "both compilers, six programs, then the two examples";
}

// Generated programs use every construct of the language; the tight node
// makes the compilers work at the edge of its stack and memory.
TEST(VerifierOnCompiledCode, AcceptsGeneratedPrograms)
{
    REQUIRE_REFERENCE();
    TargetDescription roomy = compiler_tests::dummy_node_target();
    roomy.bytecode_size = 2048;
    TargetDescription tight = compiler_tests::dummy_node_target();
    tight.bytecode_size = 300;
    tight.stack_size = 6;
    tight.variables_size = 36;
    tight.named_variables = { { "id", 1 }, { "source", 1 }, { "args", 8 } };
    aseba::CommonDefinitions definitions;
    definitions.events = { { "go", 0 }, { "ping", 1 }, { "alarm", 3 }, { "pair", 2 } };
    definitions.constants = { { "LIMIT", 5 }, { "NEGATIVE", -3 }, { "BIG", 1000 } };
    int checked = 0;
    for (const TargetDescription *target : { &roomy, &tight }) {
        compiler_tests::ProgramGenerator generator(20261123, *target, definitions);
        for (int i = 0; i < 400; i++) {
            const compiler_tests::GeneratedProgram program = generator.valid_program();
            checked += check_both_compilers("generated program " + std::to_string(i) + ":\n" +
                                              program.source,
                                            program.source,
                                            *target,
                                            definitions,
                                            nat_standard_table);
        }
    }
    EXPECT_GT(checked, 800);
}

} // namespace
