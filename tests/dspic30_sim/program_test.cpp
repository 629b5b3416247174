// dspic30-sim as a user runs it, and the Intel HEX reader under it: images
// as pic30-elf-bin2hex writes them, corrupt files, exit statuses, UART1 on
// standard input and output, and the report of a program that fails.

#include "tests/dspic30_sim/pic30_toolchain.hpp"
#include "tools/dspic30_sim/intel_hex.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace aseba::dspic30
{
namespace
{

struct ProgramRun {
    int status;
    std::string output; // standard output and error
};

// Runs dspic30-sim with `arguments` (and `input` on its standard input).
ProgramRun simulator(const std::string &arguments, const std::string &input = "")
{
    test::ScratchFolder folder;
    test::write_text_file(folder.file("input"), input);
    const std::string command =
      std::string(DSPIC30_SIM) + " " + arguments + " <" + folder.file("input") + " 2>&1";
    FILE *pipe = popen(command.c_str(), "r");
    ProgramRun run{ -1, "" };
    char buffer[4096];
    std::size_t n;
    while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0)
        run.output.append(buffer, n);
    const int status = pclose(pipe);
    run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

// An image of `source`, written to `path`.
std::string image(const test::ScratchFolder &folder,
                  const std::string &name,
                  const std::string &source)
{
    const auto program = test::assemble_program(source, 0);
    const std::string path = folder.file(name);
    test::write_text_file(path, program.hex);
    return path;
}

// UART1 at 115200 baud, then `body`.
const std::string uart_setup = R"(
        .text
        goto start
        .org 0x100
start:  mov #7, w0
        mov w0, 0x0214
        mov #0x8000, w0
        mov w0, 0x020C
        mov #0x0400, w0
        mov w0, 0x020E
)";

TEST(Program, HelpAndUsage)
{
    const ProgramRun help = simulator("--help");
    EXPECT_EQ(help.status, 0);
    EXPECT_NE(help.output.find("usage: dspic30-sim"), std::string::npos);
    EXPECT_NE(help.output.find("--uart1"), std::string::npos);
    EXPECT_NE(help.output.find("Exit status"), std::string::npos);
    EXPECT_EQ(simulator("").status, 2);
    EXPECT_EQ(simulator("--uart1 carrier-pigeon x.hex").status, 2);
    const ProgramRun missing = simulator("no-such-image.hex");
    EXPECT_EQ(missing.status, 2);
    EXPECT_NE(missing.output.find("cannot be read"), std::string::npos);
}

TEST(Program, CorruptHexIsRefusedWithItsLine)
{
    test::ScratchFolder folder;
    const std::string path = folder.file("bad.hex");
    test::write_text_file(path, ":020000040000FA\n:0400000000000000FB\n:00000001FF\n");
    const ProgramRun run = simulator(path);
    EXPECT_EQ(run.status, 2);
    EXPECT_NE(run.output.find("line 2: checksum"), std::string::npos) << run.output;
}

TEST(Program, EchoesStandardInputThroughUart1)
{
    test::ScratchFolder folder;
    const std::string path = image(folder, "echo.hex", uart_setup + R"(
wait:   btss 0x020E, #0         ; URXDA
        bra wait
        mov 0x0212, w1
        mov w1, 0x0210
        bra wait
)");
    const ProgramRun run = simulator("--uart1 stdio --cycles 2000000 " + path, "hello");
    EXPECT_EQ(run.status, 0);
    EXPECT_EQ(run.output, "hello");
}

// --input-after: nothing reaches the receiver before the cycle given. The
// program answers "E" to a byte that comes during its first 65,536 x 3
// cycles, and echoes the bytes that come after.
TEST(Program, InputAfterHoldsStandardInputBack)
{
    test::ScratchFolder folder;
    const std::string path = image(folder, "late.hex", uart_setup + R"(
        clr w2
early:  btsc 0x020E, #0         ; URXDA
        bra too_soon
        dec w2, w2
        bra nz, early
wait:   btss 0x020E, #0
        bra wait
        mov 0x0212, w1
        mov w1, 0x0210
        bra wait
too_soon:
        mov #'E', w1
        mov w1, 0x0210
spin:   bra spin
)");
    constexpr int early_cycles = 65536 * 3;
    const ProgramRun held = simulator(
      "--cycles 2000000 --input-after " + std::to_string(2 * early_cycles) + " " + path, "late");
    EXPECT_EQ(held.status, 0);
    EXPECT_EQ(held.output, "late");
    const ProgramRun at_once = simulator("--cycles 2000000 " + path, "late");
    EXPECT_EQ(at_once.output, "E");
}

TEST(Program, UntilExitGivesTheStatus)
{
    test::ScratchFolder folder;
    const auto program = [&](const char *text) {
        std::string body;
        for (const char *c = text; *c; ++c)
            body += "        mov #" + std::to_string(static_cast<int>(*c)) +
                    ", w1\n        mov w1, 0x0210\n";
        return uart_setup + body + "spin:   bra spin\n";
    };
    EXPECT_EQ(simulator("--until-exit " + image(folder, "ok.hex", program("EXIT 0\n"))).status, 0);
    const ProgramRun failed =
      simulator("--until-exit " + image(folder, "three.hex", program("EXIT 3\n")));
    EXPECT_EQ(failed.status, 1);
    EXPECT_NE(failed.output.find("EXIT 3"), std::string::npos);
    EXPECT_EQ(simulator("--until-exit " + image(folder, "abort.hex", program("ABORT\n"))).status,
              1);
}

TEST(Program, TrapStormIsReportedWithRegistersAndLastInstructions)
{
    test::ScratchFolder folder;
    const std::string path = image(folder, "storm.hex", R"(
        .text
        goto start
        .org 0x100
start:  mov #0x0901, w1
        mov [w1], w2            ; address error, and the vectors are erased
spin:   bra spin
)");
    const ProgramRun run = simulator("--cycles 10000000 " + path);
    EXPECT_EQ(run.status, 1);
    EXPECT_NE(run.output.find("trap-reset storm"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("address error at PC 0x000102"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("word read at odd address 0x0901"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("W1=0901"), std::string::npos);
    EXPECT_NE(run.output.find("last instructions"), std::string::npos);
}

TEST(Program, IllegalInstructionStops)
{
    test::ScratchFolder folder;
    const std::string path = image(folder, "illegal.hex", R"(
        .text
        goto start
        .org 0x100
start:  nop
        .pword 0xFE2000         ; BOOTSWP: not a dsPIC30F instruction
)");
    const ProgramRun run = simulator(path);
    EXPECT_EQ(run.status, 1);
    EXPECT_NE(run.output.find("illegal instruction"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find(".pword 0xfe2000"), std::string::npos) << run.output;
    EXPECT_EQ(simulator("--illegal nop --cycles 1000 " + path).status, 0);
}

TEST(Program, WallClockWatchdog)
{
    test::ScratchFolder folder;
    const std::string path = image(folder, "loop.hex", R"(
        .text
        goto start
        .org 0x100
start:  bra start
)");
    const ProgramRun run = simulator("--timeout 0.2 " + path);
    EXPECT_EQ(run.status, 1);
    EXPECT_NE(run.output.find("wall-clock watchdog"), std::string::npos) << run.output;
}

// The reader alone: bin2hex's layout and the faults it names.
TEST(IntelHex, Layout)
{
    // PC 0x000100 = byte address 0x200: the word 0x123456, then EEPROM at
    // PC 0x7FF000 (byte address 0xFFE000) through an extended address.
    const auto words = read_intel_hex(":04020000563412005E\n"
                                      ":0200000400FFFB\n"
                                      ":04E00000EFBE00006F\n"
                                      ":00000001FF\n");
    ASSERT_EQ(words.size(), 2u);
    EXPECT_EQ(words.at(0x100), 0x123456u);
    EXPECT_EQ(words.at(0x7FF000), 0xBEEFu);
}

TEST(IntelHex, Faults)
{
    const auto fault = [](const char *text) {
        try {
            read_intel_hex(text);
        } catch (const HexError &e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    EXPECT_NE(fault("04020000563412005E\n:00000001FF\n").find("line 1"), std::string::npos);
    EXPECT_NE(fault(":04020000563412005F\n:00000001FF\n").find("checksum"), std::string::npos);
    EXPECT_NE(fault(":0402000056341200\n:00000001FF\n").find("length"), std::string::npos);
    EXPECT_NE(fault(":04020000563412005E\n").find("end-of-file"), std::string::npos);
    EXPECT_NE(fault(":04020000563412015D\n:00000001FF\n").find("phantom"), std::string::npos);
    EXPECT_NE(fault(":030200005634125F\n:00000001FF\n").find("only in part"), std::string::npos);
    EXPECT_NE(fault(":04020000563412005E\n:04020000563412005E\n:00000001FF\n").find("twice"),
              std::string::npos);
    EXPECT_NE(fault(":0402000G563412005E\n:00000001FF\n").find("hexadecimal"), std::string::npos);
    EXPECT_NE(fault(":00000006FA\n:00000001FF\n").find("record type"), std::string::npos);
}

} // namespace
} // namespace aseba::dspic30
