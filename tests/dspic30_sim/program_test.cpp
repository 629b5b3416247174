// dspic30-sim as a user runs it, and the Intel HEX reader under it: images
// as pic30-elf-bin2hex writes them, corrupt files, exit statuses, UART1 on
// standard input and output, and the report of a program that fails.

#include "tests/dspic30_sim/pic30_toolchain.hpp"
#include "tools/dspic30_sim/intel_hex.hpp"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
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

// --- the memory file (--memory) ------------------------------------------

std::string file_bytes(const std::string &path)
{
    std::ifstream file(path, std::ios::binary);
    return { std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>() };
}

// Sends the low byte of the flash word at PC 0x4000 on UART1, then programs
// the whole row (32 write latches, NVMCON 0x4001: a row program, FRM §5)
// with that byte shifted right: programming only clears bits, so each run
// that finds the row as the last one left it prints the next value of FF,
// 7F, 3F...
const std::string halving_program = uart_setup + R"(
        clr w0
        mov w0, 0x0032          ; TBLPAG
        mov #0x4000, w2
        tblrdl [w2], w3
        mov w3, 0x0210          ; U1TXREG
        and #0xFF, w3
        lsr w3, w3
        mov #0x4001, w0
        mov w0, 0x0760          ; NVMCON: program a row
        mov #0xFF, w4
        mov #32, w5
fill:   tblwth w4, [w2]
        tblwtl w3, [w2++]
        dec w5, w5
        bra nz, fill
        mov #0x55, w0
        mov w0, 0x0766          ; NVMKEY
        mov #0xAA, w0
        mov w0, 0x0766
        bset 0x0760, #15        ; WR
        nop
        nop
spin:   bra spin
)";

TEST(Program, MemoryFileKeepsTheFlashBetweenRuns)
{
    test::ScratchFolder folder;
    const std::string program = image(folder, "halving.hex", halving_program);
    const std::string memory = folder.file("robot.memory");
    const std::string run = "--cycles 1000000 --memory " + memory + " ";
    const ProgramRun first = simulator(run + program);
    EXPECT_EQ(first.status, 0) << first.output;
    ASSERT_FALSE(first.output.empty());
    EXPECT_EQ(static_cast<uint8_t>(first.output[0]), 0xFF) << "an erased word reads FFFFFF";
    EXPECT_NE(first.output.find("1 NVM operations"), std::string::npos) << first.output;
    ASSERT_TRUE(std::filesystem::exists(memory));

    // The file exists: the chip starts with it, with or without the image.
    const ProgramRun second = simulator(run);
    EXPECT_EQ(second.status, 0) << second.output;
    ASSERT_FALSE(second.output.empty());
    EXPECT_EQ(static_cast<uint8_t>(second.output[0]), 0x7F);
    const ProgramRun third = simulator(run + program);
    const std::string note = "is not loaded\n"; // on standard error, before the run
    const std::size_t after_note = third.output.find(note);
    ASSERT_NE(after_note, std::string::npos) << third.output;
    ASSERT_GT(third.output.size(), after_note + note.size());
    EXPECT_EQ(static_cast<uint8_t>(third.output[after_note + note.size()]), 0x3F);
    // No temporary file is left beside it.
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(folder.path()),
                            std::filesystem::directory_iterator()),
              2);

    EXPECT_EQ(simulator("--memory " + folder.file("absent.memory")).status, 2)
      << "no image and no memory file";
}

TEST(Program, DamagedMemoryFileIsRefusedAndLeftAlone)
{
    test::ScratchFolder folder;
    const std::string program = image(folder, "halving.hex", halving_program);
    const std::string good = folder.file("good.memory");
    ASSERT_EQ(simulator("--cycles 1000 --memory " + good + " " + program).status, 0);
    const std::string contents = file_bytes(good);
    const auto refused = [&](const std::string &name, const std::string &bytes) {
        const std::string path = folder.file(name);
        test::write_text_file(path, bytes);
        const ProgramRun run = simulator("--cycles 1000 --memory " + path + " " + program);
        EXPECT_EQ(run.status, 2) << name;
        EXPECT_EQ(file_bytes(path), bytes) << name << " was overwritten";
        return run.output;
    };
    EXPECT_NE(refused("other.memory", "not a memory file\n").find("not a dspic30-sim memory file"),
              std::string::npos);
    EXPECT_NE(refused("short.memory", contents.substr(0, contents.size() - 100)).find("truncated"),
              std::string::npos);
    std::string flipped = contents;
    flipped[contents.size() / 2] = static_cast<char>(flipped[contents.size() / 2] ^ 1);
    EXPECT_NE(refused("flipped.memory", flipped).find("checksum"), std::string::npos);
}

// --power-cut-at: a row erase (NVMCON 0x4041) of a row written with
// 0x123456 everywhere, cut at its first operation, leaves the first half of
// the row erased and the second as it was (the documented choice); the
// bytes printed before and after the erase show it on the next run.
TEST(Program, PowerCutLeavesHalfARowErased)
{
    test::ScratchFolder folder;
    const std::string program = image(folder, "erase.hex", uart_setup + R"(
        clr w0
        mov w0, 0x0032          ; TBLPAG
        mov #0x4000, w2
        mov #0x403E, w6
        tblrdl [w2], w3
        mov w3, 0x0210
        tblrdl [w6], w3
        mov w3, 0x0210
        mov #0x4041, w0
        mov w0, 0x0760          ; NVMCON: erase a row
        clr w0
        mov w0, 0x0764          ; NVMADRU
        mov w2, 0x0762          ; NVMADR
        mov #0x55, w0
        mov w0, 0x0766
        mov #0xAA, w0
        mov w0, 0x0766
        bset 0x0760, #15
        nop
        nop
        tblrdl [w2], w3
        mov w3, 0x0210
        tblrdl [w6], w3
        mov w3, 0x0210
spin:   bra spin
        .org 0x4000
        .rept 32
        .pword 0x123456
        .endr
)");
    const std::string memory = folder.file("cut.memory");
    const ProgramRun whole = simulator("--cycles 1000000 " + program);
    EXPECT_EQ(whole.output, "\x56\x56\xFF\xFF");
    const ProgramRun cut =
      simulator("--cycles 1000000 --power-cut-at 1 --memory " + memory + " " + program);
    EXPECT_EQ(cut.status, 0) << cut.output;
    EXPECT_EQ(cut.output.substr(0, 2), "\x56\x56") << "nothing runs after the cut";
    EXPECT_NE(cut.output.find("power cut at NVM operation 1"), std::string::npos) << cut.output;
    const ProgramRun after = simulator("--cycles 1000000 --memory " + memory);
    EXPECT_EQ(after.output.substr(0, 4), "\xFF\x56\xFF\xFF") << after.output;
}

// --- UART1 on a TCP port --------------------------------------------------

// A client socket connected to 127.0.0.1:`port` (-1 if it cannot).
int connect_to(uint16_t port)
{
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = htons(port);
    if (connect(fd, reinterpret_cast<sockaddr *>(&address), sizeof address) != 0) {
        close(fd);
        return -1;
    }
    return fd;
}

// What arrives on `fd` within `milliseconds`, up to `wanted` bytes.
std::string receive(int fd, std::size_t wanted, int milliseconds)
{
    std::string data;
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(milliseconds);
    while (data.size() < wanted) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          end - std::chrono::steady_clock::now());
        pollfd p{ fd, POLLIN, 0 };
        if (left.count() <= 0 || poll(&p, 1, static_cast<int>(left.count())) <= 0)
            break;
        char buffer[64];
        const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
        if (n <= 0)
            break;
        data.append(buffer, static_cast<std::size_t>(n));
    }
    return data;
}

const std::string echo_program = uart_setup + R"(
wait:   btss 0x020E, #0         ; URXDA
        bra wait
        mov 0x0212, w1
        mov w1, 0x0210
        bra wait
)";

// dspic30-sim started with `arguments`, its standard output read until the
// port it announces.
struct TcpRun {
    FILE *pipe = nullptr;
    uint16_t port = 0;

    explicit TcpRun(const std::string &arguments, const std::string &uart = "UART1")
    {
        pipe = popen((std::string(DSPIC30_SIM) + " " + arguments + " 2>/dev/null").c_str(), "r");
        char line[128] = "";
        if (std::fgets(line, sizeof line, pipe) != nullptr) {
            const std::string text = line;
            const std::string prefix = "dspic30-sim: " + uart + " on tcp:localhost;";
            if (text.rfind(prefix, 0) == 0)
                port = static_cast<uint16_t>(std::stoi(text.substr(prefix.size())));
        }
    }
    int finish()
    {
        const int status = pclose(pipe);
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    }
};

TEST(Program, Uart1OnTcpEchoesOneClientAtATime)
{
    test::ScratchFolder folder;
    const std::string program = image(folder, "echo.hex", echo_program);
    // Three seconds of the robot's time: three seconds of the wall clock.
    TcpRun run("--uart1 tcp:0 --cycles 44236800 " + program);
    ASSERT_NE(run.port, 0) << "no port announced";
    const int first = connect_to(run.port);
    ASSERT_GE(first, 0);
    ASSERT_EQ(send(first, "ab", 2, 0), 2);
    EXPECT_EQ(receive(first, 2, 1000), "ab");
    // A second client is connected but not served while the first stays.
    const int second = connect_to(run.port);
    ASSERT_GE(second, 0);
    ASSERT_EQ(send(second, "cd", 2, 0), 2);
    EXPECT_EQ(receive(second, 2, 300), "");
    close(first);
    EXPECT_EQ(receive(second, 2, 1000), "cd") << "served once the first left";
    close(second);
    EXPECT_EQ(run.finish(), 0);
}

TEST(Program, Uart1OnTcpKeepsPaceWithTheWallClock)
{
    test::ScratchFolder folder;
    const std::string program = image(folder, "echo.hex", echo_program);
    const auto seconds_of = [&](const std::string &speed) {
        const auto start = std::chrono::steady_clock::now();
        TcpRun run("--uart1 tcp:0 --cycles 7372800 " + speed + program); // 0.5 s at 14.7456 MHz
        EXPECT_NE(run.port, 0);
        EXPECT_EQ(run.finish(), 0);
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    EXPECT_GE(seconds_of(""), 0.49) << "half a second of the robot's time";
    EXPECT_GE(seconds_of("--speed 4 "), 0.12) << "at four times the wall clock";
}

TEST(Program, Uart1TcpTargetsAndPortsInUse)
{
    test::ScratchFolder folder;
    const std::string program = image(folder, "echo.hex", echo_program);
    for (const char *target : { "tcp:", "tcp:65536", "tcp:12x", "tcp:-1", "udp:5000" })
        EXPECT_EQ(simulator(std::string("--uart1 ") + target + " " + program).status, 2) << target;
    // A port some other program listens on.
    const int taken = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(bind(taken, reinterpret_cast<sockaddr *>(&address), sizeof address), 0);
    ASSERT_EQ(listen(taken, 1), 0);
    socklen_t length = sizeof address;
    getsockname(taken, reinterpret_cast<sockaddr *>(&address), &length);
    const ProgramRun in_use =
      simulator("--uart1 tcp:" + std::to_string(ntohs(address.sin_port)) + " " + program);
    close(taken);
    EXPECT_EQ(in_use.status, 1);
    EXPECT_NE(in_use.output.find("Address already in use"), std::string::npos) << in_use.output;
}

// --uart2: UART2's registers (0x0216-0x021E) on their own TCP port, UART1
// unconnected; one UART at most on stdio.
TEST(Program, Uart2OnTcpEchoes)
{
    test::ScratchFolder folder;
    const std::string program = image(folder, "echo2.hex", R"(
        .text
        goto start
        .org 0x100
start:  mov #7, w0
        mov w0, 0x021E          ; U2BRG: 115200 baud
        mov #0x8000, w0
        mov w0, 0x0216          ; U2MODE
        mov #0x0400, w0
        mov w0, 0x0218          ; U2STA: UTXEN
wait:   btss 0x0218, #0         ; URXDA
        bra wait
        mov 0x021C, w1
        mov w1, 0x021A
        bra wait
)");
    TcpRun run("--uart1 none --uart2 tcp:0 --cycles 14745600 " + program, "UART2");
    ASSERT_NE(run.port, 0) << "no UART2 port announced";
    const int client = connect_to(run.port);
    ASSERT_GE(client, 0);
    ASSERT_EQ(send(client, "uv", 2, 0), 2);
    EXPECT_EQ(receive(client, 2, 1000), "uv");
    close(client);
    EXPECT_EQ(run.finish(), 0);
    const ProgramRun both = simulator("--uart1 stdio --uart2 stdio " + program);
    EXPECT_EQ(both.status, 2);
    EXPECT_NE(both.output.find("cannot both be on stdio"), std::string::npos) << both.output;
    EXPECT_EQ(simulator("--uart2 tcp:x " + program).status, 2);
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
