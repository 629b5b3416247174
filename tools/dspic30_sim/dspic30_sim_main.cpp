// dspic30-sim: runs a dsPIC30F6014A image (Intel HEX from pic30-elf-bin2hex
// or xc16-bin2hex) from reset in the simulator, with UART1 on standard input
// and output or on a loopback TCP port (an Aseba node), the chip's flash
// kept in a file between runs if asked. A run that fails (the chip
// resetting on traps over and over, an illegal instruction, the wall-clock
// watchdog, a test's ABORT) ends with a report: the traps, the registers
// and the last instructions.

#include "tools/command_line/command_line.hpp"
#include "tools/dspic30_sim/disassembler.hpp"
#include "tools/dspic30_sim/intel_hex.hpp"
#include "tools/dspic30_sim/memory_file.hpp"
#include "tools/dspic30_sim/simulator.hpp"
#include "tools/dspic30_sim/tcp_link.hpp"
#include "tools/dspic30_sim/wall_clock_pace.hpp"

#include <csignal>
#include <array>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <poll.h>
#include <string>
#include <thread>
#include <unistd.h>

namespace
{

using namespace aseba::dspic30;
namespace cl = aseba::command_line;

// The chip's instruction clock on the e-puck (7.3728 MHz crystal, PLL x8, 4
// clocks an instruction).
constexpr double chip_cycles_per_second = 14745600;
// Simulated time between two services of the TCP link: a millisecond of
// the robot's (about 11 bytes at 115,200 baud).
constexpr uint64_t tcp_slice_cycles = 14746;

constexpr const char *usage =
  "usage: dspic30-sim [--uart1 stdio|none|tcp:PORT] [--uart2 none|stdio|tcp:PORT]\n"
  "                   [--speed FACTOR] [--memory FILE]\n"
  "                   [--power-cut-at K] [--cycles N] [--timeout SECONDS]\n"
  "                   [--input-after N] [--until-exit] [--illegal stop|nop] [--trace]\n"
  "                   [IMAGE.hex]";

constexpr const char *details =
  R"(Runs IMAGE.hex on a simulated dsPIC30F6014A (the e-puck's chip) from
reset: the CPU and its DSP engine, 48 K words of flash, 8 KB of RAM, the
data EEPROM, the NVM controller, traps, interrupts, the watchdog, timers
1-5, UART1 and UART2, the I/O ports (inputs all low), the 12-bit ADC
(inputs all at 0) and the I2C master (no device on the bus); no other
peripheral yet
(docs/dspic30-sim.md says what is modelled). The image is read as
pic30-elf-bin2hex writes it: byte address = 2 x PC address, 4 bytes per
instruction word, the fourth 0.

With --uart1 stdio (the default) what the program sends on UART1 appears
on standard output and standard input feeds its receiver, at the baud rate
the program sets; --input-after holds standard input back until a given
cycle, as a host that speaks only later (after a bootloader's wait, say).
With --uart1 tcp:PORT, UART1 is a TCP server on 127.0.0.1:PORT (0: a free
port), announced on standard output as "dspic30-sim: UART1 on
tcp:localhost;PORT", and each client's arrival and departure on standard
error with the cycle: the robot is an Aseba node for the console, Studio or
asebamassloader, as over its Bluetooth link. One client at a time: a second
one is connected by the system but served only once the first leaves; with
none, what the robot sends is lost. Simulated time then keeps pace with the
wall clock at the chip's 14.7456 MHz (--speed 1), so that the firmware's
timeouts last as long as on a robot; --speed 0 runs as fast as it can.
--uart2 takes the same modes for UART2 (default none: unconnected),
announced as "dspic30-sim: UART2 on tcp:localhost;PORT"; one UART at most
on standard input and output.

With --memory FILE the flash, the data EEPROM and the configuration words
are kept in FILE between runs: when FILE exists the chip starts with it
and IMAGE.hex is not loaded (it may then be left out); otherwise IMAGE.hex
is loaded. When the run ends (its limit, Ctrl-C or SIGTERM, a power cut, a
failure), FILE receives the memory as it is, written whole to a temporary
file then renamed. A FILE that cannot be read is an error; nothing is run
or written then. --power-cut-at K stops the run as a power cut would when
the K-th NVM operation (flash row erase or write, EEPROM erase or write,
configuration word) begins: that operation reaches the first half of its
row only (a single word: not at all).

The run stops after --cycles instruction cycles, when the wall-clock
watchdog fires (--timeout), when the chip keeps resetting on traps, at a
word that is no instruction (--illegal stop), on Ctrl-C or SIGTERM, or with
--until-exit when UART1 prints a line "EXIT n" or "ABORT" (the convention
of the GCC torture tests). At 14.7456 MHz, one second of the robot's time
is 14,745,600 cycles.

Exit status: 0 when the run reached its cycle limit, printed "EXIT 0", was
stopped by Ctrl-C or SIGTERM or by its power cut; 1 when it printed
"EXIT n" (n != 0) or "ABORT", kept resetting on traps, hit an illegal
instruction or the wall-clock watchdog, or when the TCP port cannot be
opened (in use) or the memory file written; 2 on bad usage (a malformed
--uart1 or --uart2 target, both on stdio) or an image or memory file that
cannot be read or loaded.)";

struct Options {
    std::string image;
    std::string uart1 = "stdio";
    std::string uart2 = "none";
    double speed = 1;
    std::string memory;
    uint64_t power_cut_at = 0;
    uint64_t cycles = never;
    std::optional<double> timeout;
    bool until_exit = false;
    std::string illegal = "stop";
    bool trace = false;
    uint64_t input_after = 0;
};

Options parse_command_line(int argc, char **argv)
{
    Options o;
    CLI::App app(details, "dspic30-sim");
    auto formatter = cl::use_common_style(app);
    formatter->set_usage(&app, usage);
    app
      .add_option("IMAGE.hex",
                  o.image,
                  "the program, as pic30-elf-bin2hex writes it (not needed when the --memory "
                  "FILE exists)")
      ->type_name("");
    app
      .add_option("--uart1",
                  o.uart1,
                  "stdio: UART1 on standard input and output; none: unconnected;\n"
                  "tcp:PORT: a TCP server on 127.0.0.1:PORT (0: a free port)")
      ->type_name("MODE");
    app
      .add_option(
        "--uart2", o.uart2, "the same for UART2 (default none); one UART at most on stdio")
      ->type_name("MODE");
    app
      .add_option("--speed",
                  o.speed,
                  "with tcp:PORT, simulated time at FACTOR x the wall clock (default 1;\n"
                  "0: as fast as it can)")
      ->check(CLI::NonNegativeNumber)
      ->type_name("FACTOR");
    app
      .add_option(
        "--memory", o.memory, "keep flash, EEPROM and configuration words in FILE between runs")
      ->type_name("FILE");
    app
      .add_option("--power-cut-at",
                  o.power_cut_at,
                  "cut the power when the K-th NVM operation begins (it reaches half its row)")
      ->check(CLI::PositiveNumber)
      ->type_name("K");
    app
      .add_option("--input-after",
                  o.input_after,
                  "UART1 receives nothing from standard input before cycle N (default 0)")
      ->type_name("N");
    app.add_option("--cycles", o.cycles, "stop after N instruction cycles (default: no limit)")
      ->type_name("N");
    app
      .add_option("--timeout",
                  o.timeout,
                  "the wall-clock watchdog: fail after SECONDS of run time (default 60,\n"
                  "none with tcp:PORT; 0: none)")
      ->check(CLI::NonNegativeNumber)
      ->type_name("SECONDS");
    app.add_flag(
      "--until-exit",
      o.until_exit,
      "stop when UART1 prints a line \"EXIT n\" (status 0 for n = 0, else 1) or \"ABORT\" (1)");
    app
      .add_option(
        "--illegal",
        o.illegal,
        "at a word that is no instruction: stop with a report (default), or run it as a NOP")
      ->check(CLI::IsMember({ "stop", "nop" }))
      ->type_name("stop|nop");
    app.add_flag("--trace",
                 o.trace,
                 "print each instruction before it runs, with the registers, on standard error");
    cl::parse_or_exit(app, argc, argv);
    return o;
}

// Set by SIGINT and SIGTERM: the run ends at the next slice, the memory is
// written.
volatile std::sig_atomic_t stop_signal = 0;

void on_stop_signal(int)
{
    stop_signal = 1;
}

int read_standard_input()
{
    static bool ended = false;
    if (ended)
        return -1;
    pollfd fd{ STDIN_FILENO, POLLIN, 0 };
    if (poll(&fd, 1, 0) <= 0 || !(fd.revents & (POLLIN | POLLHUP)))
        return -1;
    unsigned char byte;
    if (read(STDIN_FILENO, &byte, 1) != 1) {
        ended = true;
        return -1;
    }
    return byte;
}

std::string hex(uint32_t v, int digits)
{
    char text[16];
    std::snprintf(text, sizeof text, "0x%0*X", digits, static_cast<unsigned>(v));
    return text;
}

std::string trap_name(Trap trap)
{
    switch (trap) {
    case Trap::oscillator_failure: return "oscillator failure";
    case Trap::address_error: return "address error";
    case Trap::stack_error: return "stack error";
    case Trap::math_error: return "math error";
    }
    return "?";
}

std::string instruction_text(Cpu &cpu, uint32_t pc)
{
    if (pc >= flash_end)
        return "(outside program flash)";
    const auto &memory = cpu.program_memory();
    return disassemble(pc, memory.read(pc), memory.read(pc + 2));
}

void report(Cpu &cpu, const RunResult &result)
{
    std::cerr << "dspic30-sim: stopped by " << outcome_name(result.outcome) << " after "
              << result.cycles << " cycles\n";
    if (result.trap_count > 0) {
        std::cerr << "  traps (" << result.trap_count << ", the first " << result.traps.size()
                  << "):\n";
        for (const TrapRecord &t : result.traps)
            std::cerr << "    " << trap_name(t.trap) << " at PC " << hex(t.pc, 6) << ", cycle "
                      << t.cycle << (t.cause.empty() ? "" : ": " + t.cause)
                      << (t.reset ? " (the chip reset)" : "") << "\n";
    }
    if (!result.traps.empty())
        std::cerr << "  registers at the first trap: " << result.traps.front().registers << "\n";
    std::cerr << "  registers now: " << cpu.register_summary() << "\n";
    if (result.outcome == Outcome::illegal_instruction)
        std::cerr << "  at " << hex(cpu.pc(), 6) << ": " << instruction_text(cpu, cpu.pc()) << "\n";
    std::cerr << "  last instructions:\n";
    for (uint32_t pc : cpu.last_pcs())
        std::cerr << "    " << hex(pc, 6) << "  " << instruction_text(cpu, pc) << "\n";
}

// The chip's memory at start: the --memory FILE when it exists, else the
// image. Exits (status 2) when neither can be used.
void load_memory(Simulator &simulator, const Options &options)
{
    if (!options.memory.empty() && std::filesystem::exists(options.memory)) {
        try {
            restore_memory(simulator.cpu(), read_memory_file(options.memory));
        } catch (const MemoryFileError &e) {
            std::cerr << "dspic30-sim: " << e.what() << " (left as it is)\n";
            std::exit(cl::EXIT_USAGE);
        }
        if (!options.image.empty())
            std::cerr << "dspic30-sim: the chip starts with " << options.memory << "; "
                      << options.image << " is not loaded\n";
        simulator.cpu().power_on_reset();
        return;
    }
    if (options.image.empty()) {
        cl::print_usage_error("dspic30-sim",
                              options.memory.empty()
                                ? "no IMAGE.hex given"
                                : "no IMAGE.hex given, and " + options.memory + " does not exist");
        std::exit(cl::EXIT_USAGE);
    }
    try {
        simulator.load(read_intel_hex_file(options.image));
    } catch (const HexError &e) {
        std::cerr << "dspic30-sim: " << e.what() << "\n";
        std::exit(cl::EXIT_USAGE);
    } catch (const std::invalid_argument &e) {
        std::cerr << "dspic30-sim: " << options.image << ": " << e.what() << "\n";
        std::exit(cl::EXIT_USAGE);
    }
}

// What a UART is connected to (--uart1, --uart2): nothing, standard input
// and output, or a TCP server.
struct UartEnd {
    std::string name; // "UART1"
    bool stdio = false;
    std::unique_ptr<TcpLink> link;
};

// Opens the end that `mode` names for UART `name` ("stdio", "none",
// "tcp:PORT"); exits with status 2 on a malformed mode, 1 when the port
// cannot be opened.
UartEnd open_uart_end(const std::string &name, const std::string &flag, const std::string &mode)
{
    UartEnd end;
    end.name = name;
    end.stdio = mode == "stdio";
    if (end.stdio || mode == "none")
        return end;
    uint16_t port = 0;
    try {
        port = parse_tcp_target(mode);
    } catch (const std::invalid_argument &e) {
        cl::print_usage_error("dspic30-sim", flag + ": " + e.what() + " (stdio, none or tcp:PORT)");
        std::exit(cl::EXIT_USAGE);
    }
    try {
        end.link = std::make_unique<TcpLink>(port);
    } catch (const LinkError &e) {
        std::cerr << "dspic30-sim: " << e.what() << "\n";
        std::exit(cl::EXIT_FAILED);
    }
    return end;
}

// Serves `end`'s TCP client, if any, and says on standard error when one
// arrives or leaves.
void service_uart_end(UartEnd &end, const Cpu &cpu)
{
    if (!end.link)
        return;
    const bool was_connected = end.link->connected();
    end.link->service(0);
    if (end.link->connected() == was_connected)
        return;
    // UART1's lines keep their words of before UART2 existed (scripts read them).
    std::fprintf(stderr,
                 "dspic30-sim: %sclient %s at cycle %llu (%.3f s)\n",
                 end.name == "UART1" ? "" : (end.name + " ").c_str(),
                 was_connected ? "gone" : "connected",
                 static_cast<unsigned long long>(cpu.cycles()),
                 static_cast<double>(cpu.cycles()) / chip_cycles_per_second);
}

// The exit status of a run that ended with `result`, after its report.
int run_status(Cpu &cpu, const RunResult &result)
{
    switch (result.outcome) {
    case Outcome::cycle_limit:
    case Outcome::interrupted: return cl::EXIT_OK;
    case Outcome::power_cut:
        std::cerr << "dspic30-sim: power cut at NVM operation " << cpu.nvm_operations()
                  << ", cycle " << result.cycles << "\n";
        return cl::EXIT_OK;
    case Outcome::exit_line:
        if (result.exit_status == 0)
            return cl::EXIT_OK;
        report(cpu, result);
        return cl::EXIT_FAILED;
    default: report(cpu, result); return cl::EXIT_FAILED;
    }
}

} // namespace

int main(int argc, char **argv)
{
    const Options options = parse_command_line(argc, argv);
    if (options.uart1 == "stdio" && options.uart2 == "stdio") {
        cl::print_usage_error("dspic30-sim", "--uart1 and --uart2 cannot both be on stdio");
        return cl::EXIT_USAGE;
    }
    std::array<UartEnd, 2> uarts{ open_uart_end("UART1", "--uart1", options.uart1),
                                  open_uart_end("UART2", "--uart2", options.uart2) };
    const bool any_link = uarts[0].link || uarts[1].link;

    const Cpu *chip = nullptr; // set once the simulator exists
    const auto input = [&chip, after = options.input_after]() {
        if (chip == nullptr || chip->cycles() < after)
            return -1;
        return read_standard_input();
    };
    // The byte streams of each UART's end (none: both empty).
    const auto output_of = [](UartEnd &end) -> std::function<void(uint8_t)> {
        if (end.link)
            return [&end](uint8_t byte) { end.link->write_byte(byte); };
        if (end.stdio)
            return [](uint8_t byte) {
                std::fputc(byte, stdout);
                if (byte == '\n')
                    std::fflush(stdout);
            };
        return {};
    };
    const auto input_of = [&input](UartEnd &end) -> std::function<int()> {
        if (end.link)
            return [&end]() { return end.link->read_byte(); };
        if (end.stdio)
            return input;
        return {};
    };
    Simulator simulator(output_of(uarts[0]), input_of(uarts[0]));
    if (uarts[1].link || uarts[1].stdio)
        simulator.connect_uart2(output_of(uarts[1]), input_of(uarts[1]));
    chip = &simulator.cpu();
    load_memory(simulator, options);
    Cpu &cpu = simulator.cpu();
    cpu.set_stop_on_illegal(options.illegal == "stop");
    cpu.cut_power_at_nvm_operation(options.power_cut_at);
    if (options.trace)
        cpu.set_trace([&](const Cpu &c) {
            const uint32_t pc = c.pc();
            std::fprintf(stderr,
                         "%06X  %-40s %s\n",
                         static_cast<unsigned>(pc),
                         instruction_text(cpu, pc).c_str(),
                         c.register_summary().c_str());
        });
    std::signal(SIGINT, on_stop_signal);
    std::signal(SIGTERM, on_stop_signal);

    RunLimits limits;
    limits.cycles = options.cycles;
    limits.seconds = options.timeout.value_or(any_link ? 0 : 60);
    limits.stop_at_exit_line = options.until_exit;
    WallClockPace pace(any_link ? options.speed * chip_cycles_per_second : 0);
    if (any_link) {
        for (const UartEnd &end : uarts)
            if (end.link)
                std::printf("dspic30-sim: %s on tcp:localhost;%u\n",
                            end.name.c_str(),
                            unsigned(end.link->port()));
        std::fflush(stdout);
        simulator.set_between_slices(tcp_slice_cycles, [&] {
            for (UartEnd &end : uarts)
                service_uart_end(end, cpu);
            const auto wait = pace.wait_at(cpu.cycles());
            if (wait > WallClockPace::Clock::duration::zero())
                std::this_thread::sleep_for(wait);
            return stop_signal == 0;
        });
    } else {
        simulator.set_between_slices(uint64_t{ 1 } << 22, [] { return stop_signal == 0; });
    }
    const RunResult result = simulator.run(limits);
    for (UartEnd &end : uarts)
        if (end.link)
            end.link->service(0); // the last replies
    std::fflush(stdout);
    int status = run_status(cpu, result);
    if (!options.memory.empty()) {
        try {
            write_memory_file(options.memory, capture_memory(cpu.program_memory()));
            std::cerr << "dspic30-sim: " << cpu.nvm_operations()
                      << " NVM operations; memory kept in " << options.memory << "\n";
        } catch (const MemoryFileError &e) {
            std::cerr << "dspic30-sim: " << e.what() << "\n";
            status = cl::EXIT_FAILED;
        }
    }
    return status;
}
