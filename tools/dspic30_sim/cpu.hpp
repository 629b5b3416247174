// The dsPIC30F6014A's CPU: W0-W15, SR, CORCON, the DSP engine's two
// 40-bit accumulators, REPEAT and DO loops, modulo and bit-reversed
// addressing, PSV and table access, the NVM controller, traps and
// interrupts, over the program memory and 8 KB of RAM, with peripherals on
// the SFR bus (peripheral.hpp). It executes predecoded instructions
// (predecode.hpp), counts instruction cycles as the manual gives them, and
// stops at a cycle limit, on request, or after a storm of trap resets.

#pragma once

#include "tools/dspic30_sim/memory_map.hpp"
#include "tools/dspic30_sim/peripheral.hpp"
#include "tools/dspic30_sim/predecode.hpp"
#include "tools/dspic30_sim/program_memory.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace aseba::dspic30
{

// The trap vectors (IVT slots 1-4) and their priorities (vector order:
// oscillator failure above address error above stack error above math
// error, ../shared/research/dspic30-core.md §8.1).
enum class Trap : uint8_t {
    oscillator_failure = 1,
    address_error = 2,
    stack_error = 3,
    math_error = 4,
};

// Why run() returned.
enum class StopReason : uint8_t {
    cycle_limit,         // the cycle count reached the limit given
    requested,           // request_stop() (a peripheral, the caller's watchdog)
    trap_reset_storm,    // the chip kept resetting on traps (a program that cannot run)
    illegal_instruction, // a word that is no instruction (when stop_on_illegal is set)
};

// What happened at a trap: for reports of programs that fail.
struct TrapRecord {
    Trap trap;
    uint32_t pc; // the instruction that caused it (or was about to run)
    uint64_t cycle;
    bool reset;            // a hard-trap conflict reset the chip
    std::string cause;     // in words: "word read at odd address 0x0803", ...
    std::string registers; // register_summary() when the cause was found
};

class Cpu
{
  public:
    // The number of instruction addresses kept for reports (last_pcs()).
    static constexpr int history_length = 32;
    // W15, the stack pointer.
    static constexpr int stack_pointer_register = 15;
    // Trap resets in a row (no instruction cycle in between more than
    // storm_window apart) that stop run() with trap_reset_storm.
    static constexpr int storm_resets = 8;
    static constexpr uint64_t storm_window = 1000000;

    Cpu();
    Cpu(const Cpu &) = delete;
    Cpu &operator=(const Cpu &) = delete;

    // --- setting up ---------------------------------------------------------
    // Program space as a programmer writes it (the loader; flash, EEPROM,
    // configuration). Returns false where nothing is implemented.
    bool program(uint32_t address, uint32_t word);
    const ProgramMemory &program_memory() const
    {
        return program_;
    }
    // Puts `peripheral` on the SFR addresses first..last (inclusive, even).
    void attach(uint16_t first, uint16_t last, Peripheral &peripheral);
    // A power-on reset: registers, peripherals, RCON = POR; RAM is kept.
    void power_on_reset();

    // --- running ------------------------------------------------------------
    // Runs until the cycle count reaches `cycle_limit` (or a stop).
    StopReason run(uint64_t cycle_limit);
    // Makes run() return before the next instruction.
    void request_stop();
    uint64_t cycles() const
    {
        return cycles_;
    }
    // The instructions executed since the CPU was made (each iteration of
    // a REPEAT counts).
    uint64_t instructions() const
    {
        return instructions_;
    }
    // Called before each instruction while set (a trace); empty = none.
    void set_trace(std::function<void(const Cpu &)> trace)
    {
        trace_ = std::move(trace);
    }
    // Whether run() stops at a word that is no instruction (the default;
    // else it runs as a NOP, ⚠ the dsPIC30F has no illegal-opcode trap).
    void set_stop_on_illegal(bool stop)
    {
        stop_on_illegal_ = stop;
    }
    // Called at each trap and trap reset.
    void set_trap_observer(std::function<void(const TrapRecord &)> observer)
    {
        trap_observer_ = std::move(observer);
    }

    // --- power cuts (fault injection) ---------------------------------------
    // Cuts the power when the k-th NVM operation (flash row erase or
    // program, EEPROM erase or write, configuration word; counted from 1
    // since the CPU was made) begins: that operation takes effect on the
    // first half of its row only (a single EEPROM or configuration word: not
    // at all), as the chip would leave a row whose erase or programming lost
    // its supply midway, then run() stops and power_cut() is true. 0 = never.
    void cut_power_at_nvm_operation(uint64_t k)
    {
        power_cut_at_ = k;
    }
    // The NVM operations started so far (the one cut included).
    uint64_t nvm_operations() const
    {
        return nvm_operations_;
    }
    bool power_cut() const
    {
        return power_cut_;
    }

    // --- peripherals --------------------------------------------------------
    // Sets the interrupt flag of IRQ `irq` (IFSx bit irq % 16 of irq / 16).
    void raise_interrupt(int irq);
    // Whether the flag of IRQ `irq` is set.
    bool interrupt_flag(int irq) const;
    // An oscillator failure as the fail-safe clock monitor meets it (fault
    // injection: the simulator has no clock that fails): with FOSC.FCKSM = 00
    // sets OSCCON.CF, clears OSWEN, raises the oscillator-failure trap and
    // returns true; with the monitor off (the e-puck's setting) returns false
    // and changes nothing (the real chip would stop).
    bool fail_oscillator();
    // Tells the CPU that a peripheral's next_event() moved earlier.
    void reschedule()
    {
        next_event_ = 0;
    }

    // --- the programmer's model (tests, traces, reports) --------------------
    uint16_t w(int n) const
    {
        return w_[n];
    }
    // Sets Wn (W15 with its bit 0 cleared, as the chip does).
    void set_w(int n, uint16_t value)
    {
        w_[n] = n == stack_pointer_register ? static_cast<uint16_t>(value & ~1u) : value;
    }
    uint32_t pc() const
    {
        return pc_;
    }
    void set_pc(uint32_t pc)
    {
        pc_ = pc & pc_mask;
    }
    uint16_t sr() const
    {
        return sr_;
    }
    void set_sr(uint16_t value);
    uint16_t corcon() const
    {
        return corcon_;
    }
    void set_corcon(uint16_t value);
    // Accumulator 0 (A) or 1 (B), sign-extended from 40 bits.
    int64_t accumulator(int which) const
    {
        return acc_[which];
    }
    void set_accumulator(int which, int64_t value);
    // A data-space word or byte as an instruction would read or write it
    // (SFR side effects included; traps recorded, not taken).
    uint16_t read_data(uint16_t address, bool byte = false);
    void write_data(uint16_t address, uint16_t value, bool byte = false);
    // The addresses of the last instructions executed, oldest first.
    std::vector<uint32_t> last_pcs() const;
    // Text of the CPU registers on one line: "W0=.... ... SR=.... PC=......".
    std::string register_summary() const;
    // The instruction predecoded at `pc` (decoding it if needed).
    const Decoded &instruction_at(uint32_t pc);

  private:
    friend struct Executor;

    // --- data space (cpu_memory.cpp) ----------------------------------------
    uint16_t read_word(uint16_t ea);
    uint8_t read_byte(uint16_t ea);
    void write_word(uint16_t ea, uint16_t value);
    void write_byte(uint16_t ea, uint8_t value);
    uint16_t read_slow(uint16_t ea, bool byte);
    void write_slow(uint16_t ea, uint16_t value, bool byte);
    uint16_t sfr_read(uint16_t address);
    void sfr_write(uint16_t address, uint16_t value, uint16_t mask);
    uint16_t core_sfr_read(uint16_t address);
    void core_sfr_write(uint16_t address, uint16_t value);
    // Effective addresses of the indirect modes, with the register update;
    // `size` is 1 or 2 bytes.
    uint16_t ea_modify(int mode, int reg, int size, bool write_side);
    uint16_t modulo_adjust(int reg, uint16_t old_value, uint16_t new_value, bool write_side);
    void check_stack_ea(uint16_t ea);
    void stack_error(uint16_t ea);
    // Reads / writes an operand of mode `mode` on register `reg` (`wb` is
    // the offset register of [Wn+Wb]).
    uint16_t read_operand(int mode, int reg, int wb, bool byte);
    void write_operand(int mode, int reg, int wb, bool byte, uint16_t value);
    void write_w(int reg, uint16_t value, bool byte)
    {
        w_[reg] = byte ? static_cast<uint16_t>((w_[reg] & 0xFF00) | (value & 0xFF)) : value;
    }
    void push_word(uint16_t value);
    uint16_t pop_word();
    void addressing_modes_changed();

    // --- program space (cpu_nvm.cpp) ----------------------------------------
    uint32_t table_address(uint16_t ea) const;
    uint16_t table_read(uint16_t ea, bool high, bool byte);
    void table_write(uint16_t ea, bool high, bool byte, uint16_t value);
    uint16_t psv_read(uint16_t ea, bool byte);
    void nvm_write(uint16_t address, uint16_t value, uint16_t mask);
    void nvm_start();
    void nvm_finish();
    void invalidate(uint32_t first, uint32_t end);

    // --- exceptions (cpu_exceptions.cpp) ------------------------------------
    void raise_trap(Trap trap, std::string cause);
    void recompute_interrupts();
    bool service(uint64_t cycle_limit, StopReason &reason);
    void take_exception(int vector, int level);
    void trap_reset(Trap trap);
    void device_reset(uint16_t rcon_cause);
    void return_from_interrupt();
    int cpu_priority() const;
    void restart_watchdog();

    // --- DSP engine (cpu_dsp.cpp) -------------------------------------------
    void dsp_instruction(const Decoded &d);
    int64_t multiply(uint16_t a, uint16_t b) const;
    void store_accumulator(int which, int64_t value);
    uint16_t accumulator_to_word(int64_t value, bool round) const;
    void mac_prefetch(const Decoded &d,
                      uint16_t &x_value,
                      uint16_t &y_value,
                      bool &has_x,
                      bool &has_y);
    void mac_write_back(const Decoded &d);
    static int64_t shift_accumulator(int64_t value, int shift);

    // --- execution (cpu_execute.cpp) ----------------------------------------
    template<bool traced>
    StopReason run_loop(uint64_t cycle_limit);
    void loop_end(uint32_t pc);
    void divide_step(const Decoded &d);
    void set_dsp_flags();

    ProgramMemory program_;
    std::vector<Decoded> code_; // one per flash word; op_undecoded until first fetch

    // Registers.
    std::array<uint16_t, 16> w_{};
    uint32_t pc_ = 0;
    uint16_t sr_ = 0;
    uint16_t corcon_ = corcon::RESET_VALUE;
    std::array<int64_t, 2> acc_{};
    uint16_t splim_ = 0;
    bool splim_written_ = false;
    uint16_t tblpag_ = 0;
    uint16_t psvpag_ = 0;
    uint16_t rcount_ = 0;
    uint16_t dcount_ = 0;
    uint32_t dostart_ = 0;
    uint32_t doend_ = 0;
    uint16_t modcon_ = 0;
    uint16_t xmodsrt_ = 0, xmodend_ = 0, ymodsrt_ = 0, ymodend_ = 0;
    uint16_t xbrev_ = 0;
    // One level of DO shadows, and the PUSH.S shadows.
    uint16_t dcount_shadow_ = 0;
    uint32_t dostart_shadow_ = 0, doend_shadow_ = 0;
    std::array<uint16_t, 4> w_shadow_{};
    uint16_t sr_shadow_ = 0;

    // The instruction whose completion needs the slow path (the DO loop
    // end, or the target of an active REPEAT), or `no_watch`.
    static constexpr uint32_t no_watch = 0xFFFFFFFF;
    uint32_t watch_pc_ = no_watch;
    uint32_t repeat_pc_ = 0;
    // Whether any modulo or bit-reversed addressing is enabled.
    bool special_addressing_ = false;

    // RAM and SFRs.
    std::array<uint8_t, ram_size> ram_{};
    std::array<uint16_t, sfr_end / 2> sfr_{};
    std::array<Peripheral *, sfr_end / 2> sfr_owner_{};
    std::vector<Peripheral *> peripherals_;

    // Interrupts and traps.
    uint8_t trap_pending_ = 0; // bit per Trap
    int irq_level_ = 0;        // highest pending enabled IRQ priority (0 = none)
    int irq_number_ = -1;
    uint64_t disi_end_ = 0; // cycle at which DISI stops holding levels 1-6
    int trap_resets_ = 0;
    uint64_t last_trap_reset_ = 0;
    std::string trap_cause_;
    std::string trap_registers_;
    uint32_t trap_pc_ = 0;
    bool sleeping_ = false;
    uint64_t watchdog_at_ = never;
    bool stop_on_illegal_ = true;
    bool illegal_seen_ = false;

    // NVM controller.
    uint16_t nvmcon_ = 0, nvmadr_ = 0, nvmadru_ = 0;
    int nvm_key_state_ = 0;
    uint64_t nvm_unlocked_until_ = 0;
    uint64_t nvm_done_at_ = never;
    std::array<uint32_t, flash_row_words> latches_{};
    std::array<bool, flash_row_words> latch_written_{};
    uint64_t nvm_operations_ = 0;
    uint64_t power_cut_at_ = 0;
    bool power_cut_ = false;

    // Time and control.
    uint64_t cycles_ = 0;
    uint64_t next_event_ = 0;
    bool stop_requested_ = false;
    uint32_t current_pc_ = 0; // the instruction being executed
    std::array<uint32_t, history_length> history_{};
    uint64_t instructions_ = 0; // also the next slot of history_
    std::function<void(const Cpu &)> trace_;
    std::function<void(const TrapRecord &)> trap_observer_;
};

} // namespace aseba::dspic30
