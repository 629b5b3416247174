// Upstream Aseba's compiler tests, replayed with our compiler, our VM and our
// standard natives: one test case per row of the corpus manifest, judged
// exactly as tests/vectors/upstream-compiler/README.md §2 says, except that
// every integer of a dump is compared (upstream skips an unterminated last one).

#include <gtest/gtest.h>

#include <array>
#include <map>
#include <sstream>

#include "bytecode_listing.hpp"
#include "corpus.hpp"
#include "test_targets.hpp"
#include "tools/compiler/compiler.hpp"
#include "tools/compiler/target_presets.hpp"

extern "C" {
#include "nat_standard.h"
#include "vm.h"
}

namespace compiler_tests
{

// How GoogleTest names a row in its messages.
void PrintTo(const CorpusCase &row, std::ostream *out)
{
    *out << row.test_name << " (" << row.script << ")";
}

namespace
{

// The node of README §1 and the run limits of README §2.
constexpr uint16_t node_id = 1;
constexpr uint16_t bytecode_words = 512;
constexpr uint16_t variable_words = 256;
constexpr uint16_t stack_words = 64;
constexpr uint16_t step_budget = 1000;
constexpr uint16_t local_event_test = 0xFFFE;
constexpr std::size_t standard_native_count = 30;

// The compiler's view of our natives: what the node would send in its
// NATIVE_FUNCTION_DESCRIPTION messages.
std::vector<aseba::NativeFunction> natives_of(const vm_native_table &table)
{
    return aseba::native_functions(table);
}

// What the VM reported while running; errors are what README §2.6 counts.
struct RunReport {
    int errors = 0;
    std::ostringstream log;
};

RunReport &report_of(void *context)
{
    return *static_cast<RunReport *>(context);
}

void on_emit(void *context, uint16_t event, const int16_t *, uint16_t count)
{
    report_of(context).log << "  emit event " << event << " (" << count << " words)\n";
}

void on_event_killed(void *context, uint16_t pc)
{
    report_of(context).log << "  event killed at pc " << pc << "\n";
}

void on_array_access(void *context, uint16_t pc, uint16_t size, uint16_t index)
{
    report_of(context).errors++;
    report_of(context).log << "  ARRAY_ACCESS_OUT_OF_BOUNDS pc " << pc << " size " << size
                           << " index " << index << "\n";
}

void on_division_by_zero(void *context, uint16_t pc)
{
    report_of(context).errors++;
    report_of(context).log << "  DIVISION_BY_ZERO pc " << pc << "\n";
}

void on_node_specific_error(void *context, uint16_t pc, const char *message)
{
    report_of(context).errors++;
    report_of(context).log << "  NODE_SPECIFIC_ERROR pc " << pc << ": " << message << "\n";
}

// The VM's word reports, state changes left out.
void on_report(void *context, uint16_t type, const uint16_t *words, uint16_t count)
{
    if (type == VM_REPORT_EVENT_EXECUTION_KILLED && count == 1)
        on_event_killed(context, words[0]);
    else if (type == VM_REPORT_ARRAY_ACCESS_OUT_OF_BOUNDS && count == 3)
        on_array_access(context, words[0], words[1], words[2]);
    else if (type == VM_REPORT_DIVISION_BY_ZERO && count == 1)
        on_division_by_zero(context, words[0]);
    else if (type != VM_REPORT_EXECUTION_STATE_CHANGED)
        on_node_specific_error(context, count > 0 ? words[0] : 0, "unexpected report");
}

const vm_callbacks callbacks = { on_emit, on_report, on_node_specific_error };

// The node: memory, VM and what it reported.
struct TestNode {
    std::array<uint16_t, bytecode_words> bytecode{};
    std::array<int16_t, variable_words> variables{};
    std::array<int16_t, stack_words> stack{};
    vm_state vm{};
    RunReport report;

    TestNode()
    {
        const vm_memory memory = { bytecode.data(),
                                   bytecode_words,
                                   variables.data(),
                                   variable_words,
                                   stack.data(),
                                   stack_words,
                                   0 /* no `args` variable */ };
        vm_init(&vm, &memory, node_id, &nat_standard_table, &callbacks, &report);
    }
};

const char *mode_name(CorpusMode mode)
{
    switch (mode) {
    case CorpusMode::memcmp: return "memcmp";
    case CorpusMode::event_memcmp: return "event_memcmp";
    case CorpusMode::run_ok: return "run_ok";
    case CorpusMode::exec_fail: return "exec_fail";
    case CorpusMode::comp_fail: return "comp_fail";
    }
    return "?";
}

std::string describe(const aseba::CompileError &error)
{
    std::ostringstream text;
    if (error.has_position)
        text << "Error at Line: " << error.position.line << " Col: " << error.position.column
             << " : ";
    else
        text << "Error : ";
    text << error.message;
    return text.str();
}

std::vector<CorpusCase> manifest_or_nothing()
{
    try {
        return read_corpus_manifest();
    } catch (const std::exception &) {
        return {}; // CorpusManifest.HasTheDocumentedRows reports why
    }
}

class CorpusTest : public testing::TestWithParam<CorpusCase>
{
};

TEST_P(CorpusTest, BehavesAsUpstream)
{
    const CorpusCase &row = GetParam();
    const std::string source = read_corpus_file(row.script);
    SCOPED_TRACE("script " + row.script + ", mode " + mode_name(row.mode) + "\n" + source);

    // 1. Compile.
    const aseba::CompileResult compiled =
      aseba::compile(source, corpus_target(natives_of(nat_standard_table)), corpus_definitions());
    if (row.mode == CorpusMode::comp_fail) {
        EXPECT_FALSE(compiled.ok) << "the script must not compile; it gave:\n"
                                  << bytecode_listing(compiled.bytecode);
        return;
    }
    ASSERT_TRUE(compiled.ok) << describe(compiled.error);
    ASSERT_LE(compiled.bytecode.size(), bytecode_words);

    // 2. Load as SET_BYTECODE (reset, init armed) then RUN; 3. run init.
    TestNode node;
    vm_set_bytecode(&node.vm, 0, compiled.bytecode.data(), uint16_t(compiled.bytecode.size()));
    vm_command_run(&node.vm);
    vm_run(&node.vm, step_budget);
    const std::string listing = bytecode_listing(compiled.bytecode);

    // 4. Post-init check, for every mode.
    ASSERT_FALSE(vm_is_event_active(&node.vm))
      << "init still running after " << step_budget << " steps (pc " << node.vm.pc << ")\n"
      << listing << node.report.log.str();

    // 5. The local event `test`, for event_memcmp only.
    if (row.mode == CorpusMode::event_memcmp) {
        node.vm.flags = 0;
        vm_setup_event(&node.vm, local_event_test);
        vm_run(&node.vm, step_budget);
    }

    // 6. Execution errors.
    if (row.mode == CorpusMode::exec_fail) {
        EXPECT_GT(node.report.errors, 0) << "an execution error was expected\n" << listing;
        return;
    }
    ASSERT_EQ(node.report.errors, 0) << node.report.log.str() << listing;

    // 7. Memory comparison, every integer of the dump.
    if (row.mode == CorpusMode::memcmp || row.mode == CorpusMode::event_memcmp) {
        const std::vector<int> expected = parse_dump(read_corpus_file(row.dump));
        ASSERT_LE(expected.size(), std::size_t(variable_words));
        for (std::size_t k = 0; k < expected.size(); ++k)
            EXPECT_EQ(node.variables[k], expected[k]) << "variable word " << k << "\n" << listing;
    }
}

INSTANTIATE_TEST_SUITE_P(Upstream,
                         CorpusTest,
                         testing::ValuesIn(manifest_or_nothing()),
                         [](const testing::TestParamInfo<CorpusCase> &row) {
                             return test_identifier(row.param.test_name);
                         });

// The copy of the corpus is the one its README describes.
TEST(CorpusManifest, HasTheDocumentedRows)
{
    const std::vector<CorpusCase> rows = read_corpus_manifest();
    std::map<CorpusMode, int> per_mode;
    for (const CorpusCase &row : rows)
        per_mode[row.mode]++;
    EXPECT_EQ(rows.size(), 100u);
    EXPECT_EQ(per_mode[CorpusMode::memcmp], 44);
    EXPECT_EQ(per_mode[CorpusMode::event_memcmp], 1);
    EXPECT_EQ(per_mode[CorpusMode::run_ok], 11);
    EXPECT_EQ(per_mode[CorpusMode::exec_fail], 3);
    EXPECT_EQ(per_mode[CorpusMode::comp_fail], 41);
}

// The target above is built from our native table: it must be the standard
// list of language.md §13.1 (names, parameters and their sizes, in order).
TEST(CorpusTarget, OurNativeTableIsTheStandardList)
{
    const std::vector<aseba::NativeFunction> ours = natives_of(nat_standard_table);
    const std::vector<aseba::NativeFunction> spec = standard_natives();
    ASSERT_EQ(ours.size(), standard_native_count);
    ASSERT_EQ(spec.size(), standard_native_count);
    for (std::size_t i = 0; i < spec.size(); ++i) {
        SCOPED_TRACE("native " + std::to_string(i) + " " + spec[i].name);
        EXPECT_EQ(ours[i].name, spec[i].name);
        EXPECT_EQ(ours[i].description, spec[i].description);
        ASSERT_EQ(ours[i].parameters.size(), spec[i].parameters.size());
        for (std::size_t p = 0; p < spec[i].parameters.size(); ++p) {
            EXPECT_EQ(ours[i].parameters[p].name, spec[i].parameters[p].name);
            EXPECT_EQ(ours[i].parameters[p].size, spec[i].parameters[p].size);
        }
    }
}

} // namespace
} // namespace compiler_tests
