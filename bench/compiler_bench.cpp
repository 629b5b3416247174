// The compiler benchmark: mean time to compile
//   - the paper's annex (examples/paper-annex.aesl) for the e-puck, with our
//     compiler only (the reference does not accept the paper's dialect);
//   - the same controller in today's dialect (tests/compiler/programs/
//     paper-annex.aseba) for the e-puck, with both compilers;
//   - a generated 1,000-line script in today's dialect for the dummy node
//     (with room for its bytecode), with our compiler and with the reference
//     compiler (Debian's libasebacompiler), which must produce the same words.
//
//   bench-compiler RUNS     prints one line per figure: name, ours ms, reference ms
//   bench-compiler processes RUNS
//       the whole process, start-up included: `asebac examples/paper-annex.aesl
//       -o /dev/null` beside bench-reference-compile (the reference compiler
//       behind the least of a command) on the same controller in today's
//       dialect, one after the other RUNS times; prints name, ours ms,
//       reference ms, each the median
//
// scripts/bench.sh runs it from the repo root.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <spawn.h>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "tests/compiler/reference_oracle.hpp"
#include "tools/compiler/compiler.hpp"
#include "tools/compiler/program_file.hpp"
#include "tools/compiler/target_presets.hpp"

namespace
{

// The project form of examples/paper-annex.aseba: it declares the event `bad`.
constexpr const char *paper_annex_path = "examples/paper-annex.aesl";
constexpr const char *paper_annex_today_path = "tests/compiler/programs/paper-annex.aseba";
constexpr int generated_lines = 1000;
constexpr int scalar_count = 20;
constexpr int buffer_size = 16;
constexpr uint16_t roomy_bytecode_words = 30000; // the script needs far more than 512
constexpr const char *asebac_path = "build/host/bin/asebac";
constexpr const char *reference_compile_path = "build/host/bin/bench-reference-compile";

// A deterministic script of exactly `generated_lines` lines: declarations,
// then blocks of assignments with arithmetic, array accesses, conditions,
// loops and native calls, every one valid for both compilers.
std::string generated_script()
{
    std::string text;
    int lines = 0;
    auto line = [&](const std::string &content) {
        text += content + "\n";
        lines++;
    };
    auto v = [](int k) { return "v" + std::to_string(k % scalar_count); };
    for (int k = 0; k < scalar_count; k++)
        line("var " + v(k));
    line("var buffer[" + std::to_string(buffer_size) + "]");
    line("var other[" + std::to_string(buffer_size) + "]");
    line("onevent go");
    constexpr int block_lines = 11;
    for (int k = 0; lines + block_lines <= generated_lines; k++) {
        std::string small = std::to_string(k % 7 + 1);
        std::string index = std::to_string(k % buffer_size);
        line(v(k) + " = " + v(k + 1) + " * " + small + " + buffer[" + index + "] / " +
             std::to_string(k % 5 + 1));
        line("if " + v(k) + " > " + std::to_string(k) + " and " + v(k + 2) + " != 0 then");
        line("  buffer[" + std::to_string((k + 3) % buffer_size) + "] = " + v(k + 2) + " - " +
             std::to_string(k));
        line("elseif " + v(k) + " < -" + std::to_string(k) + " then");
        line("  " + v(k + 3) + " = abs(" + v(k) + ") % 100");
        line("end");
        line("while " + v(k + 4) + " < " + small + " do");
        line("  " + v(k + 4) + " = " + v(k + 4) + " + 1");
        line("end");
        line("call math.max(other, buffer, other)");
        line("other[" + v(k + 5) + " & " + std::to_string(buffer_size - 1) + "] = (" + v(k + 6) +
             " << 2) | (" + v(k + 7) + " >> 1)");
    }
    while (lines < generated_lines)
        line("v0 = v0 + 1");
    return text;
}

template<typename Work>
double mean_ms(int runs, Work work)
{
    auto begin = std::chrono::steady_clock::now();
    for (int run = 0; run < runs; run++)
        work();
    auto end = std::chrono::steady_clock::now();
    return std::chrono::duration<double, std::milli>(end - begin).count() / runs;
}

void bench_paper_annex(int runs)
{
    aseba::ProgramFile program = aseba::read_program_file(paper_annex_path);
    aseba::TargetDescription target = aseba::epuck_target();
    std::string error_text;
    if (!aseba::compile_program_file(program, target, error_text).ok)
        throw std::runtime_error(error_text);
    double ours = mean_ms(runs, [&] { aseba::compile_program_file(program, target, error_text); });
    std::printf("paper-annex\t%.4f\t-\n", ours);
}

// Our compiler and the reference on `source`, which both must accept with
// the same bytecode; prints name, ours ms, reference ms, bytecode words.
void bench_both(const char *name,
                int runs,
                const std::string &source,
                const aseba::TargetDescription &target,
                const aseba::CommonDefinitions &definitions)
{
    aseba::CompileResult ours = aseba::compile(source, target, definitions);
    if (!ours.ok)
        throw std::runtime_error(std::string(name) + ", our compiler: line " +
                                 std::to_string(ours.error.position.line) + ": " +
                                 ours.error.message);
    reference::ReferenceResult theirs =
      reference::compile_with_reference(source, target, definitions);
    if (!theirs.ok || theirs.bytecode != ours.bytecode)
        throw std::runtime_error(std::string(name) +
                                 ": the compilers disagree: " + reference::describe(theirs));

    double ours_ms = mean_ms(runs, [&] { aseba::compile(source, target, definitions); });
    double reference_ms =
      mean_ms(runs, [&] { reference::compile_with_reference(source, target, definitions); });
    std::printf("%s\t%.4f\t%.4f\t%zu\n", name, ours_ms, reference_ms, ours.bytecode.size());
}

void bench_generated(int runs)
{
    aseba::TargetDescription target = aseba::dummy_target();
    target.bytecode_size = roomy_bytecode_words;
    aseba::CommonDefinitions definitions;
    definitions.events.push_back({ "go", 0 });
    bench_both("generated-1000", runs, generated_script(), target, definitions);
}

void bench_paper_annex_today(int runs)
{
    aseba::ProgramFile program = aseba::read_program_file(paper_annex_today_path);
    aseba::CommonDefinitions definitions;
    definitions.events.push_back({ "bad", 1 }); // as examples/paper-annex.aesl declares it
    bench_both("paper-annex-today", runs, program.source, aseba::epuck_target(), definitions);
}

// Runs `argv` to its end, its output thrown away; returns the wall-clock ms.
double process_ms(const std::vector<const char *> &argv)
{
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    std::vector<char *> arguments;
    for (const char *argument : argv)
        arguments.push_back(const_cast<char *>(argument));
    arguments.push_back(nullptr);
    auto begin = std::chrono::steady_clock::now();
    pid_t pid = -1;
    int status = -1;
    if (posix_spawn(&pid, arguments[0], &actions, nullptr, arguments.data(), environ) != 0 ||
        waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw std::runtime_error(std::string(argv[0]) + " " + argv[1] + " failed");
    auto end = std::chrono::steady_clock::now();
    posix_spawn_file_actions_destroy(&actions);
    return std::chrono::duration<double, std::milli>(end - begin).count();
}

double median_ms(std::vector<double> values)
{
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

void bench_processes(int runs)
{
    std::vector<double> ours, reference;
    for (int run = 0; run < runs; run++) {
        ours.push_back(process_ms({ asebac_path, paper_annex_path, "-o", "/dev/null" }));
        reference.push_back(process_ms({ reference_compile_path, paper_annex_today_path }));
    }
    std::printf("process-paper-annex\t%.3f\t%.3f\n", median_ms(ours), median_ms(reference));
}

} // namespace

int main(int argc, char **argv)
try {
    if (argc > 2 && std::string(argv[1]) == "processes") {
        bench_processes(std::max(1, std::atoi(argv[2])));
        return 0;
    }
    int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 10;
    if (argc > 2 && std::string(argv[2]) == "--print-generated") {
        std::fputs(generated_script().c_str(), stdout);
        return 0;
    }
    bench_paper_annex(runs * 10); // a small program: more runs for a stable mean
    bench_paper_annex_today(runs * 10);
    bench_generated(runs);
    return 0;
} catch (const std::exception &error) {
    std::fprintf(stderr, "bench-compiler: %s\n", error.what());
    return 1;
}
