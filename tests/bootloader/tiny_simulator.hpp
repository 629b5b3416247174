// A simulated e-puck with the factory Tiny Bootloader, written from the
// hardware fact sheet (§4.1-4.3), for the tests of the uploader
// (tools/flash/tiny_upload.hpp). The robot's program flash is a host board's
// (boards/epuck_host/host_board.h, with its power cuts); it talks over a
// pseudo-terminal, so the real uploader opens the slave side as it opens
// /dev/rfcomm0 (termios included).
//
// The robot runs on its own thread between start() and stop(). It starts
// "running its application", which takes bytes and answers none, until the
// user presses reset; then its reset vector runs: when it leads to the Tiny
// Bootloader (GOTO 0x017F40), Tiny waits for a first byte, answers 0xC1
// with 'q' 'K', then takes 101-byte packets (checksum, then erase and
// program the row, 'K'; a bad checksum, 'N'), until the end marker; it
// checks no address (the fact sheet: no range checking). When its first
// byte is not 0xC1 or does not come, or after the end marker, it leaves
// through its trampoline and the robot answers nothing more. A power cut
// (host_board_cut_power_at) makes the robot silent.

#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <thread>

extern "C" {
#include "boards/epuck_host/host_board.h"
}

namespace aseba::test
{

// The factory Tiny Bootloader's addresses (fact sheet §4.1).
inline constexpr uint32_t tiny_base = 0x017F00;       // its first row
inline constexpr uint32_t tiny_robot_id = 0x017F36;   // the robot number
inline constexpr uint32_t tiny_trampoline = 0x017F38; // 4 words, where it leaves
inline constexpr uint32_t tiny_entry = 0x017F40;      // the reset GOTO's target
inline constexpr uint32_t tiny_reset_instruction = 0x017FF8;
inline constexpr uint32_t clr_w0 = 0xEB0000; // the trampoline's factory words
inline constexpr uint32_t reset_opcode = 0xFE0000;

// Puts the factory state in `board`'s flash: reset GOTO 0x017F40; Tiny's
// first row erased but the robot number and 4 x `clr W0`; stand-ins for its
// code (tiny_code_word) up to 0x017FF2 and the RESET at 0x017FF8; and an old
// program (old_program_word) everywhere else below 0x017F00.
void put_factory_flash(hal_board *board, uint16_t robot_id);

// The old program's word at `pc` in the factory state (never erased, never
// a GOTO, NOP or `clr W0`).
uint32_t old_program_word(uint32_t pc);

// The stand-in for Tiny's code at `pc` in [0x017F40, 0x017FF2].
uint32_t tiny_code_word(uint32_t pc);

// Where a reset leads when no host talks to the Tiny Bootloader.
struct ResetPath {
    bool enters_tiny = false;   // the reset vector reaches the Tiny Bootloader
    bool stays_in_tiny = false; // its trampoline leads back into it
    uint32_t runs_at = 0;       // else: the first instruction reached that is no GOTO,
                                // NOP or `clr W0` (the code that then runs)
};

// Follows GOTOs, NOPs (erased words) and `clr W0` from PC 0; the Tiny
// Bootloader without a host leaves through its trampoline.
ResetPath follow_reset(const hal_board *board);

class TinySimulator
{
  public:
    static constexpr std::size_t packet_bytes = 101; // address 3, 0x60, 96 data, checksum

    // A robot in the factory state with robot number `robot_id`.
    explicit TinySimulator(uint16_t robot_id = 0);
    ~TinySimulator();

    // The slave side of the pseudo-terminal, for the uploader.
    const std::string &device() const
    {
        return device_;
    }

    // The robot's board: only while it is stopped.
    hal_board &board()
    {
        return *board_;
    }

    // How long Tiny waits for its first byte (the fact sheet: about 1 s).
    void set_first_byte_timeout(std::chrono::milliseconds timeout)
    {
        first_byte_timeout_ = timeout;
    }

    // The `number`-th packet (1 = the first) of the next run arrives with one
    // byte corrupted, once.
    void corrupt_packet(std::size_t number)
    {
        corrupt_packet_ = number;
    }

    // Starts the robot's thread; the user presses reset after `reset_after`
    // (never when empty).
    void start(std::optional<std::chrono::milliseconds> reset_after);

    // Stops the thread; what it did is then in record().
    void stop();

    struct Record {
        std::size_t resets = 0;          // resets that entered the Tiny Bootloader
        std::size_t hellos_answered = 0; // 0xC1 answered 'q' 'K'
        std::size_t packets = 0;         // complete packets received
        std::size_t rows_written = 0;    // answered 'K'
        std::size_t bad_checksums = 0;   // answered 'N'
        bool ended = false;              // the end marker arrived
        uint16_t led_ticks = 0;          // its LED time
        bool powered_off = false;        // a flash operation lost power
        bool unaligned_row = false;      // a packet's address was no row's: not modelled
    };
    const Record &record() const
    {
        return record_;
    }

  private:
    void run(std::optional<std::chrono::milliseconds> reset_after);
    void take(uint8_t byte);
    void handle_packet();
    void reset();
    void answer(std::initializer_list<uint8_t> bytes);

    enum class State { application, tiny_waiting, tiny_receiving, off };

    std::unique_ptr<hal_board> board_;
    int master_ = -1;
    int slave_ = -1; // kept open so that the master never sees a hang-up
    std::string device_;
    std::thread thread_;
    std::atomic<bool> stopping_{ false };
    std::chrono::milliseconds first_byte_timeout_{ 1000 };
    std::size_t corrupt_packet_ = 0;

    // The robot's thread's own state.
    State state_ = State::application;
    std::chrono::steady_clock::time_point tiny_deadline_;
    uint8_t packet_[packet_bytes];
    std::size_t packet_fill_ = 0;
    Record record_;
};

} // namespace aseba::test
