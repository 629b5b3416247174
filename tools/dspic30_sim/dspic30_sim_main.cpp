// dspic30-sim: runs a dsPIC30F6014A image (Intel HEX from pic30-elf-bin2hex
// or xc16-bin2hex) from reset in the simulator, with UART1 on standard input
// and output. A run that fails (the chip resetting on traps over and over,
// an illegal instruction, the wall-clock watchdog, a test's ABORT) ends
// with a report: the traps, the registers and the last instructions.

#include "tools/command_line/command_line.hpp"
#include "tools/dspic30_sim/disassembler.hpp"
#include "tools/dspic30_sim/intel_hex.hpp"
#include "tools/dspic30_sim/simulator.hpp"

#include <cstdio>
#include <iostream>
#include <poll.h>
#include <string>
#include <unistd.h>

namespace
{

using namespace aseba::dspic30;
namespace cl = aseba::command_line;

constexpr const char *usage =
  "usage: dspic30-sim [--uart1 stdio|none] [--cycles N] [--timeout SECONDS]\n"
  "                   [--input-after N] [--until-exit] [--illegal stop|nop] [--trace]\n"
  "                   IMAGE.hex";

constexpr const char *details =
  R"(Runs IMAGE.hex on a simulated dsPIC30F6014A (the e-puck's chip) from
reset: the CPU and its DSP engine, 48 K words of flash, 8 KB of RAM, the
data EEPROM, the NVM controller, traps, interrupts, the watchdog, timers
1-5 and UART1; no other peripheral yet (docs/dspic30-sim.md says what is
modelled). The image is read as
pic30-elf-bin2hex writes it: byte address = 2 x PC address, 4 bytes per
instruction word, the fourth 0.

With --uart1 stdio (the default) what the program sends on UART1 appears
on standard output and standard input feeds its receiver, at the baud rate
the program sets; --input-after holds standard input back until a given
cycle, as a host that speaks only later (after a bootloader's wait, say).
The run stops after --cycles instruction cycles, when the
wall-clock watchdog fires (--timeout), when the chip keeps resetting on
traps, at a word that is no instruction (--illegal stop), or with
--until-exit when UART1 prints a line "EXIT n" or "ABORT" (the convention
of the GCC torture tests). At 14.7456 MHz, one second of the robot's time is
14,745,600 cycles.

Exit status: 0 when the run reached its cycle limit or printed "EXIT 0"; 1
when it printed "EXIT n" (n != 0) or "ABORT", kept resetting on traps, hit
an illegal instruction or the wall-clock watchdog; 2 on bad usage or an
image that cannot be read or loaded.)";

struct Options {
    std::string image;
    std::string uart1 = "stdio";
    uint64_t cycles = never;
    double timeout = 60;
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
    app.add_option("IMAGE.hex", o.image, "the program, as pic30-elf-bin2hex writes it")
      ->required()
      ->type_name("");
    app
      .add_option(
        "--uart1", o.uart1, "stdio: UART1 on standard input and output; none: unconnected")
      ->check(CLI::IsMember({ "stdio", "none" }))
      ->type_name("MODE");
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
                  "the wall-clock watchdog: fail after SECONDS of run time (default 60; 0: none)")
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

} // namespace

int main(int argc, char **argv)
{
    const Options options = parse_command_line(argc, argv);
    std::map<uint32_t, uint32_t> words;
    try {
        words = read_intel_hex_file(options.image);
    } catch (const HexError &e) {
        std::cerr << "dspic30-sim: " << e.what() << "\n";
        return cl::EXIT_USAGE;
    }
    const bool stdio = options.uart1 == "stdio";
    const Cpu *chip = nullptr; // set once the simulator exists
    const auto input = [&chip, after = options.input_after]() {
        if (chip == nullptr || chip->cycles() < after)
            return -1;
        return read_standard_input();
    };
    Simulator simulator(
      [stdio](uint8_t byte) {
          if (!stdio)
              return;
          std::fputc(byte, stdout);
          if (byte == '\n')
              std::fflush(stdout);
      },
      stdio ? std::function<int()>(input) : std::function<int()>());
    chip = &simulator.cpu();
    try {
        simulator.load(words);
    } catch (const std::invalid_argument &e) {
        std::cerr << "dspic30-sim: " << options.image << ": " << e.what() << "\n";
        return cl::EXIT_USAGE;
    }
    Cpu &cpu = simulator.cpu();
    cpu.set_stop_on_illegal(options.illegal == "stop");
    if (options.trace)
        cpu.set_trace([&](const Cpu &c) {
            const uint32_t pc = c.pc();
            std::fprintf(stderr,
                         "%06X  %-40s %s\n",
                         static_cast<unsigned>(pc),
                         instruction_text(cpu, pc).c_str(),
                         c.register_summary().c_str());
        });
    RunLimits limits;
    limits.cycles = options.cycles;
    limits.seconds = options.timeout;
    limits.stop_at_exit_line = options.until_exit;
    const RunResult result = simulator.run(limits);
    std::fflush(stdout);
    switch (result.outcome) {
    case Outcome::cycle_limit: return cl::EXIT_OK;
    case Outcome::exit_line:
        if (result.exit_status == 0)
            return cl::EXIT_OK;
        report(cpu, result);
        return cl::EXIT_FAILED;
    default: report(cpu, result); return cl::EXIT_FAILED;
    }
}
