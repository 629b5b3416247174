// The simulated factory Tiny Bootloader (tiny_simulator.hpp), from the
// hardware fact sheet §4.1-4.3.

#include "tests/bootloader/tiny_simulator.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <stdexcept>

namespace aseba::test
{
namespace
{

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

constexpr uint32_t pc_step = 2; // PC units per instruction
constexpr uint32_t row_span = 0x40;
constexpr std::size_t row_instructions = 32;
constexpr uint32_t instruction_mask = 0xFFFFFF;
constexpr uint32_t erased = 0xFFFFFF; // also executes as a NOP
constexpr uint32_t goto_opcode = 0x04;
constexpr uint32_t goto_high_mask = 0x7F;
constexpr uint32_t tiny_code_end = 0x017FF2; // its last instruction, about (§4.1)
constexpr uint32_t flash_end = 0x018000;
constexpr std::size_t follow_steps = 1024;

// The packet (§4.2): PC address (3 bytes, little-endian), 0x60, 32 x 3
// bytes, checksum; the end marker is 4 bytes whose 4th is 0xFF.
constexpr std::size_t header_bytes = 4;
constexpr std::size_t end_marker_byte = 3;
constexpr uint8_t end_marker = 0xFF;
constexpr uint8_t hello = 0xC1;
constexpr uint8_t device_type = 0x71;
constexpr std::size_t corrupted_byte = 50;
constexpr uint8_t corruption = 0x5A;
constexpr milliseconds idle_poll{ 10 }; // how often the thread looks at `stopping_`

uint32_t flash_at(const hal_board *board, uint32_t pc)
{
    return board->flash[pc / pc_step];
}

} // namespace

uint32_t old_program_word(uint32_t pc)
{
    return 0x200000 | pc / pc_step;
}

uint32_t tiny_code_word(uint32_t pc)
{
    return 0x300000 | pc / pc_step;
}

void put_factory_flash(hal_board *board, uint16_t robot_id)
{
    for (uint32_t pc = 0; pc < tiny_base; pc += pc_step)
        board->flash[pc / pc_step] = old_program_word(pc);
    // The reset vector as the fact sheet gives its bytes: 40 7F 04 00 01 00 00 00.
    board->flash[0] = 0x40 | 0x7F << 8 | 0x04 << 16;
    board->flash[1] = 0x01;
    for (uint32_t pc = tiny_base; pc < flash_end; pc += pc_step)
        board->flash[pc / pc_step] = erased;
    board->flash[tiny_robot_id / pc_step] = robot_id;
    for (uint32_t pc = tiny_trampoline; pc < tiny_entry; pc += pc_step)
        board->flash[pc / pc_step] = clr_w0;
    for (uint32_t pc = tiny_entry; pc <= tiny_code_end; pc += pc_step)
        board->flash[pc / pc_step] = tiny_code_word(pc);
    board->flash[tiny_reset_instruction / pc_step] = reset_opcode;
}

ResetPath follow_reset(const hal_board *board)
{
    ResetPath path;
    uint32_t pc = 0;
    for (std::size_t step = 0; step < follow_steps && pc < flash_end; step++) {
        if (pc == tiny_entry) {
            if (path.enters_tiny) {
                path.stays_in_tiny = true;
                return path;
            }
            path.enters_tiny = true; // no 0xC1 within its second: it leaves
            pc = tiny_trampoline;
            continue;
        }
        uint32_t word = flash_at(board, pc);
        if (word >> 16 == goto_opcode) {
            pc = (word & 0xFFFE) | (flash_at(board, pc + pc_step) & goto_high_mask) << 16;
        } else if (word == erased || word == clr_w0) {
            pc += pc_step;
        } else {
            path.runs_at = pc;
            return path;
        }
    }
    path.runs_at = pc;
    return path;
}

TinySimulator::TinySimulator(uint16_t robot_id)
  : board_(std::make_unique<hal_board>())
{
    host_board_init(board_.get(), nullptr, nullptr);
    put_factory_flash(board_.get(), robot_id);
    master_ = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (master_ < 0 || grantpt(master_) != 0 || unlockpt(master_) != 0)
        throw std::runtime_error("no pseudo-terminal");
    char name[128];
    if (ptsname_r(master_, name, sizeof name) != 0)
        throw std::runtime_error("no pseudo-terminal name");
    device_ = name;
    slave_ = open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
    termios settings{};
    if (slave_ < 0 || tcgetattr(slave_, &settings) != 0)
        throw std::runtime_error("cannot open " + device_);
    cfmakeraw(&settings); // no echo before the uploader sets its own mode
    tcsetattr(slave_, TCSANOW, &settings);
    fcntl(master_, F_SETFL, fcntl(master_, F_GETFL) | O_NONBLOCK);
}

TinySimulator::~TinySimulator()
{
    stop();
    close(slave_);
    close(master_);
}

void TinySimulator::start(std::optional<milliseconds> reset_after)
{
    stop();
    uint8_t stale[256]; // bytes of an earlier run: heard by nobody
    while (read(master_, stale, sizeof stale) > 0) {
    }
    record_ = Record{};
    stopping_ = false;
    thread_ = std::thread(&TinySimulator::run, this, reset_after);
}

void TinySimulator::stop()
{
    stopping_ = true;
    if (thread_.joinable())
        thread_.join();
}

void TinySimulator::run(std::optional<milliseconds> reset_after)
{
    state_ = board_->powered_off ? State::off : State::application;
    auto reset_at = reset_after ? Clock::now() + *reset_after : Clock::time_point::max();
    while (!stopping_) {
        auto now = Clock::now();
        if (now >= reset_at) {
            reset_at = Clock::time_point::max();
            reset();
        }
        if (state_ == State::tiny_waiting && now >= tiny_deadline_)
            state_ = State::application; // no byte: Tiny leaves through its trampoline
        auto wake =
          std::min({ now + idle_poll,
                     reset_at,
                     state_ == State::tiny_waiting ? tiny_deadline_ : Clock::time_point::max() });
        auto timeout = std::chrono::duration_cast<milliseconds>(wake - now).count();
        pollfd waiting{ master_, POLLIN, 0 };
        if (poll(&waiting, 1, static_cast<int>(std::max<long>(timeout, 0))) <= 0)
            continue;
        uint8_t bytes[256];
        ssize_t count = read(master_, bytes, sizeof bytes);
        for (ssize_t i = 0; i < count; i++)
            take(bytes[i]);
    }
}

void TinySimulator::reset()
{
    if (board_->powered_off) {
        state_ = State::off;
        return;
    }
    if (!follow_reset(board_.get()).enters_tiny) {
        state_ = State::application; // whatever the reset vector leads to: silent here
        return;
    }
    record_.resets++;
    state_ = State::tiny_waiting;
    tiny_deadline_ = Clock::now() + first_byte_timeout_;
    packet_fill_ = 0;
}

void TinySimulator::take(uint8_t byte)
{
    switch (state_) {
    case State::application:
    case State::off: return;
    case State::tiny_waiting:
        if (byte == hello) {
            record_.hellos_answered++;
            answer({ device_type, 'K' });
            state_ = State::tiny_receiving;
        } else {
            state_ = State::application; // a stray byte: Tiny leaves
        }
        return;
    case State::tiny_receiving:
        packet_[packet_fill_++] = byte;
        if (packet_fill_ == header_bytes && packet_[end_marker_byte] == end_marker) {
            record_.ended = true;
            record_.led_ticks = static_cast<uint16_t>(packet_[0] | packet_[1] << 8);
            state_ = State::application; // LED, then the trampoline
        } else if (packet_fill_ == packet_bytes) {
            packet_fill_ = 0;
            handle_packet();
        }
        return;
    }
}

void TinySimulator::handle_packet()
{
    record_.packets++;
    if (record_.packets == corrupt_packet_) {
        packet_[corrupted_byte] ^= corruption; // noise on the line, once
        corrupt_packet_ = 0;
    }
    uint8_t sum = 0;
    for (uint8_t byte : packet_)
        sum = static_cast<uint8_t>(sum + byte);
    if (sum != 0) {
        record_.bad_checksums++;
        answer({ 'N' });
        return;
    }
    uint32_t address = packet_[0] | packet_[1] << 8 | static_cast<uint32_t>(packet_[2]) << 16;
    uint32_t row[row_instructions];
    for (std::size_t i = 0; i < row_instructions; i++) {
        const uint8_t *bytes = packet_ + header_bytes + 3 * i;
        row[i] =
          (bytes[0] | bytes[1] << 8 | static_cast<uint32_t>(bytes[2]) << 16) & instruction_mask;
    }
    // Tiny checks no address; the host board takes only whole rows, which
    // every packet of the factory uploaders is.
    if (address % row_span != 0 || address >= flash_end) {
        record_.unaligned_row = true;
        state_ = State::off;
        return;
    }
    if (!hal_flash_erase(board_.get(), address) ||
        !hal_flash_program(board_.get(), address, row, row_instructions)) {
        record_.powered_off = true;
        state_ = State::off;
        return;
    }
    record_.rows_written++;
    answer({ 'K' });
}

void TinySimulator::answer(std::initializer_list<uint8_t> bytes)
{
    if (write(master_, bytes.begin(), bytes.size()) != static_cast<ssize_t>(bytes.size()))
        throw std::runtime_error("the pseudo-terminal takes no reply");
}

} // namespace aseba::test
