// ports/dspic30 on the simulated chip: each routine's register values against
// the fact sheet's numbers (written here as the sheet gives them, not taken
// from the HAL's constants), and the UART, ADC, I2C and flash/EEPROM paths
// end to end.

#include "simulated_chip.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <memory>
#include <vector>

extern "C" {
#include "robots/epuck/devices/epuck_devices.h"
#include "firmware/firmware.h"
#include "boards/epuck_dspic30/epuck_dspic30_board.h"
#include "ports/dspic30/dspic30_startup.h"
extern const uint16_t dspic30_config_FOSC;
extern const uint16_t dspic30_config_FWDT;
extern const uint16_t dspic30_config_FBORPOR;
}

namespace
{

// Fact sheet §1.6, §2: clock and register addresses.
constexpr double FCY = 7372800.0 * 8 / 4;
constexpr uint16_t SR = 0x0042, INTCON1 = 0x0080, INTCON2 = 0x0082;
constexpr uint16_t IFS0 = 0x0084, IFS1 = 0x0086, IEC0 = 0x008C, IEC1 = 0x008E;
constexpr uint16_t IPC0 = 0x0094, IPC1 = 0x0096, IPC2 = 0x0098, IPC5 = 0x009E;
constexpr uint16_t TMR1 = 0x0100, PR1 = 0x0102, T1CON = 0x0104, PR2 = 0x010C, T2CON = 0x0110;
constexpr uint16_t PR4 = 0x011A, PR5 = 0x011C, T4CON = 0x011E, T5CON = 0x0120;
constexpr uint16_t U1MODE = 0x020C, U1STA = 0x020E, U1BRG = 0x0214;
constexpr uint16_t I2CBRG = 0x0204, I2CCON = 0x0206;
constexpr uint16_t ADCBUF0 = 0x0280, ADCON1 = 0x02A0, ADCON2 = 0x02A2, ADCON3 = 0x02A4,
                   ADCHS = 0x02A6, ADPCFG = 0x02A8, ADCSSL = 0x02AA;
constexpr uint16_t TRISA = 0x02C0, LATA = 0x02C4, TRISC = 0x02CC, TRISD = 0x02D2, LATD = 0x02D6,
                   TRISF = 0x02DE, TRISG = 0x02E4, PORTG = 0x02E6;
constexpr uint16_t TBLPAG = 0x0032, NVMCON = 0x0760, NVMADR = 0x0762, NVMADRU = 0x0764,
                   NVMKEY = 0x0766;

uint16_t field(uint16_t value, int high, int low)
{
    return uint16_t((value >> low) & ((1u << (high - low + 1)) - 1));
}

// The interrupt sources the board uses: their enable bit and their
// priority field, where the fact sheet puts them (§1.7 table, §2.6).
struct Source {
    const char *name;
    uint16_t enable_register;
    uint16_t enable_bit;
    uint16_t priority_register;
    int high, low; // the priority field's bits
};
constexpr Source int0{ "INT0", IEC0, 0x0001, IPC0, 2, 0 };
constexpr Source t1{ "T1", IEC0, 0x0008, IPC0, 14, 12 };
constexpr Source t2{ "T2", IEC0, 0x0040, IPC1, 10, 8 };
constexpr Source t3{ "T3", IEC0, 0x0080, IPC1, 14, 12 };
constexpr Source u1rx{ "U1RX", IEC0, 0x0200, IPC2, 6, 4 };
constexpr Source u1tx{ "U1TX", IEC0, 0x0400, IPC2, 10, 8 };
constexpr Source adc{ "ADC", IEC0, 0x0800, IPC2, 14, 12 };
constexpr Source t4{ "T4", IEC1, 0x0020, IPC5, 6, 4 };
constexpr Source t5{ "T5", IEC1, 0x0040, IPC5, 10, 8 };
constexpr Source sources[] = { int0, t1, t2, t3, u1rx, u1tx, adc, t4, t5 };

uint16_t priority(simulated::Chip &chip, const Source &source)
{
    return field(chip.sfr(source.priority_register), source.high, source.low);
}

// §1.7: priorities are 1 to 7, and 0 disables the source: its interrupt
// would never be taken, whatever its enable bit says.
::testing::AssertionResult can_interrupt(simulated::Chip &chip, const Source &source)
{
    uint16_t level = priority(chip, source);
    if (level >= 1 && level <= 7)
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << source.name << " has priority " << level << ": the chip would never take it";
}

struct Dspic30 : ::testing::Test {
    simulated::Chip chip;
    hal_board board{};
    void SetUp() override
    {
        dspic30_board_init(&board);
    }

    // The writes to `address` since the board started, in order.
    std::vector<uint16_t> writes_to(uint16_t address) const
    {
        std::vector<uint16_t> values;
        for (auto write : chip.writes)
            if (write.address == address)
                values.push_back(write.value);
        return values;
    }
};

TEST_F(Dspic30, ConfigurationWordsSelectTheCrystalWithPllTimesEight)
{
    // §1.5: FCKSM = 1x, FOS = 111, FPR = 00110 (XT w/PLL 8x); [HDR] gives 0xBFE6.
    EXPECT_EQ(dspic30_config_FOSC, 0xBFE6);
    EXPECT_EQ(field(dspic30_config_FOSC, 4, 0), 0b00110);
    EXPECT_EQ(field(dspic30_config_FOSC, 10, 8), 0b111);
    EXPECT_EQ(field(dspic30_config_FOSC, 15, 15), 1);
    EXPECT_EQ(dspic30_config_FWDT, 0x7FFF);
    EXPECT_EQ(dspic30_config_FBORPOR, 0xFF7F);
    EXPECT_EQ(double(DSPIC30_FCY_HZ), FCY);
}

TEST_F(Dspic30, InterruptControllerAllowsNestingOnThePrimaryVectors)
{
    EXPECT_EQ(chip.sfr(INTCON1) & 0x8000, 0); // NSTDIS
    EXPECT_EQ(chip.sfr(INTCON2) & 0x8000, 0); // ALTIVT
    EXPECT_EQ(chip.sfr(INTCON2) & 0x0001, 1); // INT0 on falling edges (§3.9)
}

TEST_F(Dspic30, MillisecondClockCountsTimer1Ticks)
{
    // Timer1 at 1:1 with a period of exactly 1/1024 s.
    EXPECT_EQ(chip.sfr(PR1) + 1, FCY / 1024);
    EXPECT_EQ(chip.sfr(T1CON), 0x8000); // TON, TCKPS = 00, internal clock
    EXPECT_EQ(chip.sfr(TMR1), 0);
    EXPECT_NE(chip.sfr(IEC0) & 0x0008, 0);
    EXPECT_TRUE(can_interrupt(chip, t1));
    for (int i = 0; i < 512; i++) {
        chip.sfr(IFS0) |= 0x0008;
        dspic30_on_clock_tick(&board);
        EXPECT_EQ(chip.sfr(IFS0) & 0x0008, 0);
    }
    EXPECT_EQ(hal_milliseconds(&board), 500u);
    for (int i = 0; i < 1024 * 3 + 1; i++)
        dspic30_on_clock_tick(&board);
    EXPECT_EQ(hal_milliseconds(&board), uint32_t(std::floor((512 + 3073) * 1000.0 / 1024)));
}

TEST_F(Dspic30, Uart1RunsAt115200EightNOneWithReceiveInterrupt)
{
    // §2.1: BRG = FCY / (16 × baud) − 1 = 7, exact.
    EXPECT_EQ(chip.sfr(U1BRG), 7);
    EXPECT_EQ(FCY / (16 * (chip.sfr(U1BRG) + 1)), 115200.0);
    uint16_t mode = chip.sfr(U1MODE);
    EXPECT_EQ(mode & 0x8000, 0x8000);   // UARTEN
    EXPECT_EQ(mode & 0x0400, 0);        // ALTIO: main pins
    EXPECT_EQ(field(mode, 2, 1), 0b00); // PDSEL 8N1
    EXPECT_EQ(mode & 1, 0);             // one stop bit
    uint16_t status = chip.sfr(U1STA);
    EXPECT_EQ(status & 0x0400, 0x0400); // UTXEN
    EXPECT_EQ(field(status, 7, 6), 0);  // URXISEL: every byte
    // The UART is enabled before the transmitter, as the data sheet asks.
    auto modes = writes_to(U1MODE);
    ASSERT_FALSE(modes.empty());
    EXPECT_EQ(modes.back(), 0x8000);
    EXPECT_EQ(status & 0x8000, 0x8000);    // UTXISEL: when the buffer empties, as the library
    EXPECT_NE(chip.sfr(IEC0) & 0x0200, 0); // U1RXIE
    EXPECT_EQ(chip.sfr(IEC0) & 0x0400, 0); // U1TXIE: only while bytes wait
    // §2.1: the library runs both UART1 interrupts at priority 5.
    EXPECT_EQ(priority(chip, u1rx), 5);
    EXPECT_EQ(priority(chip, u1tx), 5);
}

TEST_F(Dspic30, ReceivedBytesGoThroughTheRingToTheLink)
{
    // A full 522-byte frame arriving 4 bytes (one FIFO) per interrupt.
    std::vector<uint8_t> frame(522);
    for (size_t i = 0; i < frame.size(); i++)
        frame[i] = uint8_t(i * 7 + 3);
    for (size_t i = 0; i < frame.size(); i += 4) {
        for (size_t j = i; j < i + 4 && j < frame.size(); j++)
            chip.uart_receive.push_back(frame[j]);
        chip.sfr(IFS0) |= 0x0200;
        dspic30_on_uart1_receive(&board);
        EXPECT_EQ(chip.sfr(IFS0) & 0x0200, 0);
    }
    std::vector<uint8_t> received(600);
    uint16_t count = hal_link_receive(&board, received.data(), uint16_t(received.size()));
    received.resize(count);
    EXPECT_EQ(received, frame);
    EXPECT_EQ(hal_link_receive(&board, received.data(), 1), 0);
}

TEST_F(Dspic30, RingDropsBytesWhenFullInsteadOfOverwriting)
{
    for (int i = 0; i < 1100; i++) {
        chip.uart_receive.push_back(uint8_t(i));
        dspic30_on_uart1_receive(&board);
    }
    std::vector<uint8_t> received(2000);
    uint16_t count = hal_link_receive(&board, received.data(), uint16_t(received.size()));
    ASSERT_GE(count, 522);
    for (uint16_t i = 0; i < count; i++)
        ASSERT_EQ(received[i], uint8_t(i));
    EXPECT_EQ(board.link.receive_overruns, 1100 - count);
}

// The ring is one frame, not a power of two: bytes keep their order across
// its end, again and again.
TEST_F(Dspic30, RingKeepsTheOrderAcrossItsEnd)
{
    std::vector<uint8_t> received(HAL_LINK_RECEIVE_CAPACITY);
    uint8_t next_in = 0, next_out = 0;
    for (int round = 0; round < 7; round++) {
        for (int i = 0; i < 300; i++) {
            chip.uart_receive.push_back(next_in++);
            dspic30_on_uart1_receive(&board);
        }
        uint16_t count = hal_link_receive(&board, received.data(), uint16_t(received.size()));
        ASSERT_EQ(count, 300);
        for (uint16_t i = 0; i < count; i++)
            ASSERT_EQ(received[i], next_out++);
    }
    EXPECT_EQ(board.link.receive_overruns, 0);
}

TEST_F(Dspic30, OverrunIsCleared)
{
    chip.sfr(U1STA) |= 0x0002; // OERR
    dspic30_on_uart1_receive(&board);
    EXPECT_EQ(chip.sfr(U1STA) & 0x0002, 0);
}

// Sending never waits for the line: the ring takes what fits, the
// transmit buffer gets 4 bytes at once, and each time the line empties it
// the interrupt refills it, until the ring is empty.
TEST_F(Dspic30, LinkSendQueuesAndTheTransmitInterruptDrains)
{
    std::vector<uint8_t> bytes(600);
    for (size_t i = 0; i < bytes.size(); i++)
        bytes[i] = uint8_t(i * 7 + 3);
    EXPECT_EQ(hal_link_send_room(&board), HAL_LINK_TRANSMIT_CAPACITY);
    uint16_t taken = hal_link_send(&board, bytes.data(), uint16_t(bytes.size()));
    ASSERT_EQ(taken, HAL_LINK_TRANSMIT_CAPACITY);
    EXPECT_EQ(chip.uart_fifo.size(), 4u);
    EXPECT_EQ(hal_link_send_room(&board), 4);
    EXPECT_NE(chip.sfr(IEC0) & 0x0400, 0); // U1TXIE while bytes wait
    EXPECT_EQ(hal_link_send(&board, bytes.data(), 10), 4);

    int interrupts = 0;
    while (chip.uart_shift_out()) {
        if ((chip.sfr(IFS0) & 0x0400) && (chip.sfr(IEC0) & 0x0400)) {
            dspic30_on_uart1_transmit(&board);
            interrupts++;
            EXPECT_EQ(chip.sfr(IFS0) & 0x0400, 0);
        }
    }
    std::vector<uint8_t> expected(bytes.begin(), bytes.begin() + taken);
    expected.insert(expected.end(), bytes.begin(), bytes.begin() + 4);
    EXPECT_EQ(chip.uart_sent, expected);
    EXPECT_EQ(chip.uart_lost, 0);                              // never written while full
    EXPECT_EQ(interrupts, (int(expected.size()) + 3) / 4 - 1); // one per 4 bytes after the first
    EXPECT_EQ(chip.sfr(IEC0) & 0x0400, 0);                     // nothing left: U1TXIE off
    EXPECT_EQ(hal_link_send_room(&board), HAL_LINK_TRANSMIT_CAPACITY);
}

// A frame longer than the ring goes out whole and in order when the sender
// queues what fits and waits for the transmit interrupt between tries, as
// the firmware's main loop does.
TEST_F(Dspic30, FrameLongerThanTheTransmitRingGoesOutWhole)
{
    std::vector<uint8_t> frame(522);
    for (size_t i = 0; i < frame.size(); i++)
        frame[i] = uint8_t(i * 13 + 1);
    ASSERT_LT(HAL_LINK_TRANSMIT_CAPACITY, frame.size());
    size_t queued = 0;
    while (queued < frame.size()) {
        queued += hal_link_send(&board, frame.data() + queued, uint16_t(frame.size() - queued));
        // The line sends a byte; the interrupt refills the UART's buffer.
        if (chip.uart_shift_out() && (chip.sfr(IFS0) & 0x0400) && (chip.sfr(IEC0) & 0x0400))
            dspic30_on_uart1_transmit(&board);
    }
    while (chip.uart_shift_out()) {
        if ((chip.sfr(IFS0) & 0x0400) && (chip.sfr(IEC0) & 0x0400))
            dspic30_on_uart1_transmit(&board);
    }
    EXPECT_EQ(chip.uart_sent, frame);
    EXPECT_EQ(chip.uart_lost, 0);
    EXPECT_EQ(hal_link_send_room(&board), HAL_LINK_TRANSMIT_CAPACITY);
}

// The firmware on this HAL with a host that sends at the line's rate while
// the robot sends: each time the CPU idles, one byte time passes, in which
// the line takes one byte of the transmit buffer and brings one of the
// host's. No byte may be lost to the receive ring (one frame) while the
// main loop waits for its own frames to drain.
struct Dspic30Firmware : Dspic30 {
    std::unique_ptr<robot_devices> devices = std::make_unique<robot_devices>();
    std::unique_ptr<firmware_state> firmware = std::make_unique<firmware_state>();
    std::deque<uint8_t> host_sends;

    void SetUp() override
    {
        Dspic30::SetUp();
        firmware_init(firmware.get(), &board, devices.get(), 1);
        chip.on_idle = [this] { byte_time(); };
    }

    void byte_time()
    {
        if (chip.uart_shift_out() && (chip.sfr(IFS0) & 0x0400) && (chip.sfr(IEC0) & 0x0400))
            dspic30_on_uart1_transmit(&board);
        if (!host_sends.empty()) {
            chip.uart_receive.push_back(host_sends.front());
            host_sends.pop_front();
            chip.sfr(IFS0) |= 0x0200;
            dspic30_on_uart1_receive(&board);
        }
    }

    void send(uint16_t type, const std::vector<uint16_t> &payload)
    {
        std::vector<uint16_t> words{ uint16_t(payload.size() * 2), 0, type };
        words.insert(words.end(), payload.begin(), payload.end());
        for (uint16_t word : words) {
            host_sends.push_back(uint8_t(word & 0xFF));
            host_sends.push_back(uint8_t(word >> 8));
        }
    }

    // The main loop, as the application's, until the line is quiet.
    void run()
    {
        for (int pass = 0; pass < 100000; pass++) {
            if (firmware_poll(firmware.get()))
                continue;
            if (host_sends.empty() && chip.uart_fifo.empty() &&
                !hal_link_rings_sending(&board.link))
                return;
            hal_idle(&board);
        }
        FAIL() << "the line never went quiet";
    }

    // The frames the robot sent, as (type, payload words).
    std::vector<std::pair<uint16_t, std::vector<uint16_t>>> frames() const
    {
        std::vector<std::pair<uint16_t, std::vector<uint16_t>>> found;
        const auto &bytes = chip.uart_sent;
        auto word = [&](size_t at) { return uint16_t(bytes[at] | bytes[at + 1] << 8); };
        for (size_t at = 0; at + 6 <= bytes.size();) {
            uint16_t length = word(at);
            std::vector<uint16_t> payload;
            for (size_t i = 0; i + 1 < length && at + 6 + i + 1 < bytes.size(); i += 2)
                payload.push_back(word(at + 6 + i));
            found.emplace_back(word(at + 4), payload);
            at += 6 + length;
        }
        return found;
    }
};

TEST_F(Dspic30Firmware, HostSendingWhileTheRobotAnswersLosesNothing)
{
    // The largest answer, then, while it goes out, a frame of the largest
    // size setting 256 variables and a request for them back.
    std::vector<uint16_t> values(256);
    for (size_t i = 0; i < values.size(); i++)
        values[i] = uint16_t(i * 251 + 7);
    const uint16_t start = EPUCK_NAMED_WORDS; // the first the robot does not write
    send(NODE_MSG_GET_VARIABLES, { 1, 0, NODE_MAX_VARIABLES_WORDS });
    std::vector<uint16_t> set{ 1, start };
    set.insert(set.end(), values.begin(), values.end());
    send(NODE_MSG_SET_VARIABLES, set);
    send(NODE_MSG_GET_VARIABLES, { 1, start, 256 });
    ASSERT_EQ(host_sends.size(), 12u + 522u + 12u);
    run();

    EXPECT_EQ(board.link.receive_overruns, 0);
    EXPECT_EQ(firmware->node.errors.truncated, 0);
    auto sent = frames();
    ASSERT_EQ(sent.size(), 2u);
    EXPECT_EQ(sent[0].first, NODE_MSG_VARIABLES);
    EXPECT_EQ(sent[0].second.size(), 1u + NODE_MAX_VARIABLES_WORDS);
    EXPECT_EQ(sent[1].first, NODE_MSG_VARIABLES);
    std::vector<uint16_t> expected{ start };
    expected.insert(expected.end(), values.begin(), values.end());
    EXPECT_EQ(sent[1].second, expected);
}

// While the firmware waits for frames of its own to drain, bytes go on into
// the node's frame: more than the receive ring holds arrive meanwhile.
TEST_F(Dspic30Firmware, BytesGoOnIntoTheNodeWhileItsFramesDrain)
{
    // The variables the robot does not write, in two parts.
    const uint16_t start = EPUCK_NAMED_WORDS, middle = uint16_t(start + 256);
    std::vector<uint16_t> first(256), second(FIRMWARE_FREE_VARIABLE_WORDS - 256);
    for (size_t i = 0; i < first.size(); i++)
        first[i] = uint16_t(i * 31 + 5);
    for (size_t i = 0; i < second.size(); i++)
        second[i] = uint16_t(i * 17 + 9);
    std::vector<uint16_t> set{ 1, start };
    set.insert(set.end(), first.begin(), first.end());
    send(NODE_MSG_SET_VARIABLES, set);
    set = { 1, middle };
    set.insert(set.end(), second.begin(), second.end());
    send(NODE_MSG_SET_VARIABLES, set);
    send(NODE_MSG_GET_VARIABLES, { 1, start, uint16_t(first.size()) });
    send(NODE_MSG_GET_VARIABLES, { 1, middle, uint16_t(second.size()) });
    size_t to_send = host_sends.size();
    std::vector<int16_t> event(258, 3);
    node_send_user_event(&firmware->node, 7, event.data(), uint16_t(event.size()));
    node_send_user_event(&firmware->node, 8, event.data(), uint16_t(event.size()));
    EXPECT_GT(to_send - host_sends.size(), HAL_LINK_RECEIVE_CAPACITY); // arrived meanwhile
    run();

    EXPECT_EQ(board.link.receive_overruns, 0);
    auto sent = frames();
    ASSERT_EQ(sent.size(), 4u);
    EXPECT_EQ(sent[0].first, 7);
    EXPECT_EQ(sent[1].first, 8);
    EXPECT_EQ(sent[1].second, std::vector<uint16_t>(258, 3));
    std::vector<uint16_t> expected{ start };
    expected.insert(expected.end(), first.begin(), first.end());
    EXPECT_EQ(sent[2].second, expected);
    expected = { middle };
    expected.insert(expected.end(), second.begin(), second.end());
    EXPECT_EQ(sent[3].second, expected);
}

// The right motor's timer is Timer2 (Timer4 counts the camera's rows).
TEST_F(Dspic30, Timer2At100MicrosecondsMatchesTheLibrarysAgenda)
{
    int calls = 0;
    auto count = [](void *context) { ++*static_cast<int *>(context); };
    ASSERT_TRUE(epuck_board_timer_start(&board, EPUCK_TIMER_MOTOR_RIGHT, 100, count, &calls));
    // §3.13: the library's 0.1 ms agenda uses PR2 = 1474 at 1:1.
    EXPECT_EQ(chip.sfr(PR2), 1474);
    EXPECT_EQ(chip.sfr(T2CON), 0x8000);
    EXPECT_NE(chip.sfr(IEC0) & 0x0040, 0);
    EXPECT_TRUE(can_interrupt(chip, t2));
    chip.sfr(IFS0) |= 0x0040;
    dspic30_on_timer(&board, EPUCK_TIMER_MOTOR_RIGHT);
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(chip.sfr(IFS0) & 0x0040, 0);
    epuck_board_timer_stop(&board, EPUCK_TIMER_MOTOR_RIGHT);
    EXPECT_EQ(chip.sfr(T2CON) & 0x8000, 0);
    EXPECT_EQ(chip.sfr(IEC0) & 0x0040, 0);
}

// Periods against (PR + 1) × prescale / FCY (§2.2), with the smallest
// prescaler that fits 16 bits.
TEST_F(Dspic30, MotorTimerPeriodsUseTheSmallestFittingPrescaler)
{
    const uint16_t prescale[] = { 1, 8, 64, 256 };
    for (uint32_t microseconds : { 20u, 1000u, 4000u, 25000u, 100000u, 1000000u }) {
        for (epuck_timer timer : { EPUCK_TIMER_MOTOR_LEFT, EPUCK_TIMER_MOTOR_RIGHT }) {
            ASSERT_TRUE(epuck_board_timer_start(&board, timer, microseconds, nullptr, nullptr));
            // Left motor on Timer5, right on Timer2 (Timer4 is the camera's).
            uint16_t control = chip.sfr(timer == EPUCK_TIMER_MOTOR_LEFT ? T5CON : T2CON);
            uint16_t period = chip.sfr(timer == EPUCK_TIMER_MOTOR_LEFT ? PR5 : PR2);
            int code = field(control, 5, 4);
            EXPECT_EQ(control & 0x8000, 0x8000);
            EXPECT_EQ(control & 0x000A, 0); // 16-bit, internal clock
            double counts = microseconds * 1e-6 * FCY / prescale[code];
            EXPECT_NEAR(period + 1, counts, 0.5) << microseconds;
            if (code > 0) {
                EXPECT_GT(microseconds * 1e-6 * FCY / prescale[code - 1], 65536.0);
            }
        }
    }
    EXPECT_NE(chip.sfr(IEC1) & 0x0040, 0); // T5IE
    EXPECT_NE(chip.sfr(IEC0) & 0x0040, 0); // T2IE
    EXPECT_TRUE(can_interrupt(chip, t2));
    EXPECT_TRUE(can_interrupt(chip, t5));
    EXPECT_FALSE(epuck_board_timer_start(&board, EPUCK_TIMER_SPARE, 2000000, nullptr, nullptr));
    EXPECT_FALSE(epuck_board_timer_start(&board, EPUCK_TIMER_SPARE, 1, nullptr, nullptr));
    (void)IFS1;
}

TEST_F(Dspic30, AdcStartsInManualModeWithValidConversionClock)
{
    EXPECT_EQ(chip.sfr(ADPCFG), 0x0003); // AN0/AN1 digital (ICD lines), the rest analog
    EXPECT_EQ(chip.sfr(ADCON1), 0x8000); // ADON, unsigned integers, SSRC = 000
    EXPECT_EQ(chip.sfr(ADCON2), 0);      // AVdd/AVss, no scan
    uint16_t adcs = field(chip.sfr(ADCON3), 5, 0);
    double tad = (adcs + 1) / 2.0 / FCY;
    EXPECT_GE(tad, 667e-9); // §2.3 minimum at 3.3 V
    EXPECT_TRUE(can_interrupt(chip, adc));
}

TEST_F(Dspic30, SingleConversionReadsTheChannel)
{
    chip.analog[EPUCK_ADC_ACCELEROMETER_Y] = 2345;
    chip.analog[EPUCK_ADC_PROXIMITY_0 + 3] = 17;
    EXPECT_EQ(epuck_board_adc_read(&board, 6), 2345);
    EXPECT_EQ(chip.sfr(ADCHS), 6);
    EXPECT_EQ(epuck_board_adc_read(&board, 11), 17);
    EXPECT_EQ(epuck_board_adc_read(&board, 16), 0);
}

TEST_F(Dspic30, ScansInterruptAt16384HzLikeTheLibrary)
{
    struct Scan {
        uint16_t mask;
        uint16_t gctronic_adcs; // §2.3, advanced scan driver
    };
    for (Scan scan : { Scan{ 0x001C, 39 }, Scan{ 0x111C, 23 }, Scan{ 0x00FC, 19 } }) {
        ASSERT_TRUE(epuck_board_adc_scan_start(&board, scan.mask, nullptr, nullptr));
        EXPECT_EQ(chip.sfr(ADCSSL), scan.mask);
        int channels = __builtin_popcount(scan.mask);
        EXPECT_EQ(chip.sfr(ADCON1), 0x80E4);                         // ADON, SSRC = 111, ASAM
        EXPECT_EQ(chip.sfr(ADCON2), 0x0400 | ((channels - 1) << 2)); // CSCNA, SMPI
        EXPECT_EQ(field(chip.sfr(ADCON3), 12, 8), 1);                // SAMC
        uint16_t adcs = field(chip.sfr(ADCON3), 5, 0);
        EXPECT_EQ(adcs, scan.gctronic_adcs);
        double scan_seconds = channels * (1 + 14) * ((adcs + 1) / 2.0) / FCY;
        EXPECT_DOUBLE_EQ(1 / scan_seconds, 16384.0);
        EXPECT_NE(chip.sfr(IEC0) & 0x0800, 0);
    }
    EXPECT_FALSE(epuck_board_adc_scan_select(&board, 0x0004)); // one channel
    EXPECT_FALSE(epuck_board_adc_scan_select(&board, 0xFF00)); // eight
    epuck_board_adc_scan_stop(&board);
    EXPECT_EQ(chip.sfr(IEC0) & 0x0800, 0);
    EXPECT_EQ(chip.sfr(ADCON1), 0x8000);
}

TEST_F(Dspic30, ScanInterruptHandsTheBufferToTheCallback)
{
    std::vector<uint16_t> got;
    auto keep = [](void *context, const uint16_t *values, uint8_t count) {
        static_cast<std::vector<uint16_t> *>(context)->assign(values, values + count);
    };
    ASSERT_TRUE(epuck_board_adc_scan_start(&board, 0x221C, keep, &got));
    for (uint16_t i = 0; i < 5; i++)
        chip.sfr(uint16_t(ADCBUF0 + 2 * i)) = uint16_t(1000 + i);
    chip.sfr(IFS0) |= 0x0800;
    dspic30_on_adc(&board);
    EXPECT_EQ(got, (std::vector<uint16_t>{ 1000, 1001, 1002, 1003, 1004 }));
    EXPECT_EQ(chip.sfr(IFS0) & 0x0800, 0);
    EXPECT_EQ(epuck_board_adc_read(&board, 5), 0); // no single reads while scanning
    ASSERT_TRUE(epuck_board_adc_scan_select(&board, 0x00FC));
    EXPECT_EQ(chip.sfr(ADCSSL), 0x00FC);
}

TEST_F(Dspic30, I2cWritesAndReadsCameraRegisters)
{
    EXPECT_EQ(chip.sfr(I2CBRG), 150); // the library's value (§2.4)
    EXPECT_EQ(chip.sfr(I2CCON) & 0x8000, 0x8000);
    chip.i2c_devices[0xDC] = std::vector<uint8_t>(256, 0);
    chip.i2c_devices[0xDC][0x00] = 0x30;
    chip.i2c_devices[0xDC][0x01] = 0x30;
    uint8_t id[2] = {};
    ASSERT_TRUE(epuck_board_i2c_read(&board, EPUCK_I2C_CAMERA_ADDRESS, 0x00, id, 2));
    EXPECT_EQ(id[0], 0x30); // PO3030K (§3.5)
    EXPECT_EQ(id[1], 0x30);
    const uint8_t gains[] = { 0x10, 0x40, 0x40 };
    ASSERT_TRUE(epuck_board_i2c_write(&board, 0xDC, 0x15, gains, 3));
    EXPECT_EQ(chip.i2c_devices[0xDC][0x15], 0x10);
    EXPECT_EQ(chip.i2c_devices[0xDC][0x17], 0x40);
    // The last byte read gets a NACK (ACKDT = 1).
    EXPECT_NE(chip.sfr(I2CCON) & 0x0020, 0);
    EXPECT_FALSE(epuck_board_i2c_read(&board, 0x3C, 0x0F, id, 1)); // nobody at 0x3C
    EXPECT_FALSE(epuck_board_i2c_write(&board, 0x3C, 0x0F, gains, 1));
}

TEST_F(Dspic30, PortsFollowThePinMap)
{
    // §3.1: LEDs on RA6,7,9,10,12..15 are outputs, started low.
    EXPECT_EQ(chip.sfr(TRISA) & 0xF6C0, 0);
    EXPECT_EQ(chip.sfr(LATA) & 0xF6C0, 0);
    EXPECT_EQ(chip.sfr(TRISD), 0xFF00);          // motors out, camera data in
    EXPECT_EQ(chip.sfr(TRISG) & 0x03C0, 0x03C0); // selector in
    EXPECT_EQ(chip.sfr(TRISG) & 0x0003, 0);      // IR pulses 2/6, 3/7 out
    EXPECT_EQ(chip.sfr(TRISF) & 0x0180, 0);      // IR pulses 0/4, 1/5 out
    EXPECT_EQ(chip.sfr(TRISF) & 0x0042, 0x0042); // remote, battery low in
    EXPECT_EQ(chip.sfr(TRISC) & 0x2006, 0);      // front, body LED, camera reset out
    epuck_board_pin_write(&board, EPUCK_PIN_LED_3, true);
    EXPECT_EQ(chip.sfr(LATA), 1u << 12); // LED3 is RA12
    epuck_board_pin_write(&board, EPUCK_PIN_MOTOR_RIGHT_C, true);
    EXPECT_EQ(chip.sfr(LATD), 1u << 6);
    EXPECT_TRUE(epuck_board_pin_read(&board, EPUCK_PIN_MOTOR_RIGHT_C));
    epuck_board_pin_write(&board, EPUCK_PIN_SELECTOR_0, true); // an input: ignored
    chip.sfr(PORTG) = 0x0280;                                  // RG7, RG9
    int selector = 0;
    for (int bit = 0; bit < 4; bit++)
        selector |= epuck_board_pin_read(&board, epuck_pin(EPUCK_PIN_SELECTOR_0 + bit)) << bit;
    EXPECT_EQ(selector, 0b1010);
}

// A camera row is read in steps that never wait: while no frame comes, a
// step returns at once, and the read fails once nothing came for half a
// second.
TEST_F(Dspic30, CameraStepsNeverWaitForAFrame)
{
    constexpr uint16_t PORTC = TRISC + 2;
    for (uint16_t vsync : { 0x0000, 0x0010 }) { // RC4 (§3.5): between frames, in one
        chip.sfr(PORTC) = vsync;
        uint8_t bytes[2 * EPUCK_CAMERA_PIXEL_BYTES] = {};
        epuck_board_camera_start(&board, 10, bytes, 2);
        for (int step = 0; step < 5; step++)
            EXPECT_EQ(epuck_board_camera_step(&board), EPUCK_CAMERA_READING);
        for (int tick = 0; tick < 520; tick++) // Timer1 ticks of 1/1024 s: 508 ms
            dspic30_on_clock_tick(&board);
        EXPECT_EQ(epuck_board_camera_step(&board), EPUCK_CAMERA_FAILED);
        EXPECT_EQ(epuck_board_camera_step(&board), EPUCK_CAMERA_FAILED); // until started again
        EXPECT_EQ(chip.sfr(T4CON) & 0x8000, 0);
    }
}

} // namespace

// What the timed row read (dspic30_camera_row.c, dsPIC assembly) was asked,
// and what it answers.
static struct {
    int calls = 0;
    uint8_t *bytes = nullptr;
    uint16_t pixels = 0;
    bool answer = true;
} row_read;

extern "C" bool dspic30_camera_read_row(uint8_t *bytes, uint16_t pixels, uint16_t polls)
{
    (void)polls;
    row_read.calls++;
    row_read.bytes = bytes;
    row_read.pixels = pixels;
    return row_read.answer;
}

namespace
{

// §3.5, §2.2: between two frames (VSYNC inactive) a step sets Timer4
// counting HREF's rising edges on T4CK (TCS, 1:1) to interrupt at the row
// above the line (from 1 to PR4 = the line: the line-th edge), and not
// while a frame passes; the interrupt, with HREF between two rows and
// Timer4 having seen the line's edge only, reads the line once.
TEST_F(Dspic30, CameraCountsRowsOnTimer4AndReadsTheLineInItsInterrupt)
{
    constexpr uint16_t PORTC = TRISC + 2, TMR4 = 0x0114;
    EXPECT_LT(priority(chip, t4), priority(chip, u1rx)); // its wait lets UART1 in
    uint8_t bytes[60 * EPUCK_CAMERA_PIXEL_BYTES] = {};

    chip.sfr(PORTC) = 0x0010; // VSYNC active: a frame is passing
    epuck_board_camera_start(&board, 32, bytes, 60);
    EXPECT_EQ(epuck_board_camera_step(&board), EPUCK_CAMERA_READING);
    EXPECT_EQ(chip.sfr(T4CON) & 0x8000, 0);

    chip.sfr(PORTC) = 0x0000; // the blank between frames
    EXPECT_EQ(epuck_board_camera_step(&board), EPUCK_CAMERA_READING);
    EXPECT_EQ(chip.sfr(T4CON), 0x8002);
    EXPECT_EQ(chip.sfr(PR4), 32);
    EXPECT_EQ(chip.sfr(TMR4), 1);
    EXPECT_NE(chip.sfr(IEC1) & 0x0020, 0);

    row_read = {};
    chip.sfr(TMR4) = 1; // the line's HREF edge after the match
    dspic30_on_camera_row(&board);
    EXPECT_EQ(row_read.calls, 1);
    EXPECT_EQ(row_read.bytes, bytes);
    EXPECT_EQ(row_read.pixels, 60);
    EXPECT_EQ(chip.sfr(T4CON) & 0x8000, 0);
    EXPECT_EQ(chip.sfr(IEC1) & 0x0020, 0);
    EXPECT_EQ(epuck_board_camera_step(&board), EPUCK_CAMERA_DONE);

    // Line 0 has no row above it: the line below is read.
    epuck_board_camera_start(&board, 0, bytes, 60);
    EXPECT_EQ(epuck_board_camera_step(&board), EPUCK_CAMERA_READING);
    EXPECT_EQ(chip.sfr(PR4), 1);
}

// The interrupt came a row late (Timer4 saw two edges by the end of the
// read), HREF never came, or the line was already passing: the read fails.
TEST_F(Dspic30, CameraReadFailsWhenTheLineWasMissed)
{
    constexpr uint16_t PORTC = TRISC + 2, TMR4 = 0x0114;
    uint8_t bytes[60 * EPUCK_CAMERA_PIXEL_BYTES] = {};
    struct Case {
        uint16_t tmr4;
        bool answer;
        uint16_t portc;
        int calls;
    };
    for (Case c : { Case{ 2, true, 0x0000, 1 },
                    Case{ 1, false, 0x0000, 1 },
                    Case{ 1, true, 0x0008, 0 } }) { // RC3: HREF still active
        chip.sfr(PORTC) = 0x0000;
        epuck_board_camera_start(&board, 32, bytes, 60);
        EXPECT_EQ(epuck_board_camera_step(&board), EPUCK_CAMERA_READING);
        row_read = {};
        row_read.answer = c.answer;
        chip.sfr(PORTC) = c.portc;
        chip.sfr(TMR4) = c.tmr4;
        dspic30_on_camera_row(&board);
        EXPECT_EQ(row_read.calls, c.calls);
        EXPECT_EQ(epuck_board_camera_step(&board), EPUCK_CAMERA_FAILED) << c.tmr4 << c.answer;
    }
}

TEST_F(Dspic30, RemoteEdgesComeFromInt0)
{
    int edges = 0;
    auto count = [](void *context) { ++*static_cast<int *>(context); };
    EXPECT_FALSE(epuck_board_pin_watch_falling_edge(&board, EPUCK_PIN_SELECTOR_0, count, &edges));
    ASSERT_TRUE(epuck_board_pin_watch_falling_edge(&board, EPUCK_PIN_REMOTE, count, &edges));
    EXPECT_NE(chip.sfr(IEC0) & 0x0001, 0);
    EXPECT_TRUE(can_interrupt(chip, int0));
    dspic30_on_remote_edge(&board);
    EXPECT_EQ(edges, 1);
    epuck_board_pin_unwatch(&board, EPUCK_PIN_REMOTE);
    EXPECT_EQ(chip.sfr(IEC0) & 0x0001, 0);
}

// Every source the board uses has a priority the chip takes, set at
// start-up (§1.7: the reset value of the fields is not documented).
TEST_F(Dspic30, EveryInterruptTheBoardUsesCanBeTaken)
{
    for (const Source &source : sources)
        EXPECT_TRUE(can_interrupt(chip, source));
}

// The order follows from the timings: a scan's 5 results are overwritten
// 61 µs later (16384 Hz, §2.3), UART1's 4-byte buffers fill or empty in
// 347 µs (§2.1), a motor step may come a few µs late, and the millisecond
// clock's ticks are 977 µs apart.
TEST_F(Dspic30, PrioritiesFollowHowLongEachSourceCanWait)
{
    EXPECT_GT(priority(chip, adc), priority(chip, u1rx));
    for (const Source &timer : { t2, t3, t5 }) {
        EXPECT_GT(priority(chip, u1rx), priority(chip, timer)) << timer.name;
        EXPECT_GT(priority(chip, timer), priority(chip, t1)) << timer.name;
        // Timer4's camera interrupt waits for a row (a quarter of a
        // millisecond): the remote's samples and the motors' steps cannot.
        EXPECT_GT(priority(chip, timer), priority(chip, t4)) << timer.name;
    }
}

// The checks above can fail: a field cleared to 0 is caught.
TEST_F(Dspic30, APriorityOfZeroIsCaught)
{
    for (const Source &source : sources) {
        uint16_t &field_register = chip.sfr(source.priority_register);
        uint16_t saved = field_register;
        field_register = uint16_t(field_register & ~(0x7u << source.low));
        EXPECT_FALSE(can_interrupt(chip, source)) << source.name;
        field_register = saved;
    }
}

TEST_F(Dspic30, CriticalSectionRaisesCpuPriorityToSeven)
{
    chip.sfr(SR) = 0x0001; // IPL 0, carry set
    hal_critical_state outer = hal_critical_enter(&board);
    EXPECT_EQ(field(chip.sfr(SR), 7, 5), 7);
    hal_critical_state inner = hal_critical_enter(&board);
    hal_critical_leave(&board, inner);
    EXPECT_EQ(field(chip.sfr(SR), 7, 5), 7);
    hal_critical_leave(&board, outer);
    EXPECT_EQ(chip.sfr(SR), 0x0001);
}

TEST_F(Dspic30, FlashRowEraseWriteReadEndToEnd)
{
    const uint32_t row = 0x012340 & ~0x3Fu; // a row in the third panel (page 1)
    ASSERT_TRUE(hal_flash_erase(&board, row));
    ASSERT_EQ(chip.operations.size(), 1u);
    // §1.3: NVMCON 0x4041, NVMADRU:NVMADR written before the keys.
    EXPECT_EQ(chip.operations[0].nvmcon, 0x4041);
    EXPECT_EQ(chip.operations[0].address, row);
    EXPECT_EQ(writes_to(NVMADRU).back(), row >> 16);
    EXPECT_EQ(writes_to(NVMADR).back(), row & 0xFFFF);
    EXPECT_EQ(chip.rejected_unlocks, 0);

    std::vector<uint32_t> instructions(32);
    for (uint32_t i = 0; i < 32; i++)
        instructions[i] = (0xA5u << 16) | (i * 0x0101u) | 0x8000u;
    ASSERT_TRUE(hal_flash_program(&board, row, instructions.data(), 32));
    ASSERT_EQ(chip.operations.size(), 2u);
    EXPECT_EQ(chip.operations[1].nvmcon, 0x4001);
    EXPECT_EQ(chip.operations[1].address, row);
    EXPECT_EQ(writes_to(TBLPAG).back(), row >> 16);
    for (uint32_t i = 0; i < 32; i++)
        EXPECT_EQ(hal_flash_read(&board, row + 2 * i), instructions[i]) << i;
    EXPECT_EQ(hal_flash_read(&board, row + 0x40), 0xFFFFFFu); // next row untouched
    EXPECT_FALSE(hal_flash_erase(&board, row + 2));           // not a row start
    EXPECT_FALSE(hal_flash_erase(&board, 0x018000));          // past the end
}

TEST_F(Dspic30, UnlockIsKeyFiveFiveKeyAAThenWriteWithInterruptsMasked)
{
    ASSERT_TRUE(dspic30_eeprom_erase_word(&board, 3));
    // The writes around the key sequence: mask (SR), 0x55, 0xAA, WR set
    // on the erase code, nothing between them.
    size_t n = chip.writes.size();
    size_t first_key = n;
    for (size_t i = 0; i < n; i++)
        if (chip.writes[i].address == NVMKEY) {
            first_key = i;
            break;
        }
    ASSERT_GE(first_key, 1u);
    ASSERT_LT(first_key + 2, n);
    EXPECT_EQ(chip.writes[first_key - 1].address, SR);
    EXPECT_EQ(field(chip.writes[first_key - 1].value, 7, 5), 7);
    EXPECT_EQ(chip.writes[first_key].value, 0x55);
    EXPECT_EQ(chip.writes[first_key + 1].address, NVMKEY);
    EXPECT_EQ(chip.writes[first_key + 1].value, 0xAA);
    EXPECT_EQ(chip.writes[first_key + 2].address, NVMCON);
    EXPECT_EQ(chip.writes[first_key + 2].value, 0x4044 | 0x8000);
    // The operation code was in NVMCON before the keys.
    bool code_before = false;
    for (size_t i = 0; i < first_key; i++)
        if (chip.writes[i].address == NVMCON && chip.writes[i].value == 0x4044)
            code_before = true;
    EXPECT_TRUE(code_before);
    EXPECT_EQ(field(chip.operations.back().status_register, 7, 5), 7);
    EXPECT_EQ(chip.rejected_unlocks, 0);
}

TEST_F(Dspic30, EepromWordEraseWriteReadEndToEnd)
{
    const uint16_t index = 1000;
    ASSERT_TRUE(dspic30_eeprom_erase_word(&board, index));
    // §1.4: NVMCON 0x4044, NVMADRU = 0x7F, NVMADR = 0xF000 + 2 × index.
    EXPECT_EQ(chip.operations.back().nvmcon, 0x4044);
    EXPECT_EQ(chip.operations.back().address, 0x7FF000u + 2 * index);
    ASSERT_TRUE(dspic30_eeprom_write_word(&board, index, 0x1234));
    EXPECT_EQ(chip.operations.back().nvmcon, 0x4004);
    EXPECT_EQ(chip.operations.back().address, 0x7FF000u + 2 * index);
    EXPECT_EQ(writes_to(TBLPAG).back(), 0x7F);
    EXPECT_EQ(chip.eeprom[index], 0x1234);
    EXPECT_EQ(dspic30_eeprom_read(&board, index), 0x1234);
    EXPECT_EQ(dspic30_eeprom_read(&board, index + 1), 0xFFFF);
    // Without an erase, bits only go down.
    ASSERT_TRUE(dspic30_eeprom_write_word(&board, index, 0xFF0F));
    EXPECT_EQ(dspic30_eeprom_read(&board, index), 0x1204);
    EXPECT_FALSE(dspic30_eeprom_write_word(&board, 2048, 0));
}

TEST_F(Dspic30, IdleAndResetUseTheirInstructions)
{
    hal_idle(&board);
    hal_reset(&board);
    ASSERT_GE(chip.specials.size(), 2u);
    EXPECT_EQ(chip.specials[chip.specials.size() - 2], "pwrsav #1");
    EXPECT_EQ(chip.specials.back(), "reset");
}

} // namespace

// Every period the board accepts, against the exact rational count
// round(microseconds × FCY / (prescale × 10^6)) in 64 bits (§2.2): the
// port computes it in 32 bits, for the dsPIC has no 64-bit helpers.
TEST_F(Dspic30, TimerPeriodsAreExactInThirtyTwoBits)
{
    const uint64_t fcy = 7372800ull * 8 / 4;
    const uint64_t prescale[] = { 1, 8, 64, 256 };
    for (uint32_t microseconds = 20; microseconds <= 1000000; microseconds += 7) {
        uint16_t period = 0, code = 0;
        ASSERT_TRUE(dspic30_timer_period(microseconds, &period, &code)) << microseconds;
        uint64_t scale = prescale[code] * 1000000ull;
        uint64_t counts = (uint64_t(microseconds) * fcy + scale / 2) / scale;
        ASSERT_EQ(uint64_t(period) + 1, counts) << microseconds;
    }
}

// The start-up's data initialisation (dspic30_startup.c) against a
// template laid out as the linker writes it with --no-pack-data (records of
// destination, length in bytes, format; 0 clears, 1 copies two bytes per
// program word; a zero destination ends), placed across a 64 K boundary of
// program memory so that TBLPAG must move on.
TEST_F(Dspic30, StartUpFillsRamFromTheLinkersTemplate)
{
    const uint32_t template_pc = 0xFFF8;
    const std::vector<uint32_t> words = {
        0x0800, 5, 1, 0x2211, 0x4433, 0x0055, // copy 11 22 33 44 55 to 0x0800
        0x0900, 4, 0,                         // clear 0x0900..0x0903
        0x0000,                               // end
    };
    for (size_t i = 0; i < words.size(); ++i)
        chip.flash[template_pc / 2 + i] = words[i];
    chip.ram[0x0805] = 0x77; // just past the odd-length copy: untouched
    ASSERT_TRUE(dspic30_initialise_data(template_pc));
    EXPECT_EQ(std::vector<uint8_t>(chip.ram.begin() + 0x0800, chip.ram.begin() + 0x0806),
              (std::vector<uint8_t>{ 0x11, 0x22, 0x33, 0x44, 0x55, 0x77 }));
    EXPECT_EQ(std::vector<uint8_t>(chip.ram.begin() + 0x0900, chip.ram.begin() + 0x0905),
              (std::vector<uint8_t>{ 0, 0, 0, 0, simulated::Chip::ram_fill }));
}

TEST_F(Dspic30, StartUpRefusesAPackedTemplate)
{
    const uint32_t template_pc = 0x4000;
    const std::vector<uint32_t> words = { 0x0800, 3, 2, 0x332211, 0x0000 }; // format 2: packed
    for (size_t i = 0; i < words.size(); ++i)
        chip.flash[template_pc / 2 + i] = words[i];
    EXPECT_FALSE(dspic30_initialise_data(template_pc));
    EXPECT_EQ(chip.ram[0x0800], simulated::Chip::ram_fill);
}

// A program with no data at all: the linker gives the template's address as
// 0, where the reset GOTO lies, which must not be read as records.
TEST_F(Dspic30, StartUpWithoutATemplateWritesNothing)
{
    chip.flash[0] = 0x040200; // GOTO 0x000200, as the reset vector holds
    chip.flash[1] = 0x000000;
    EXPECT_TRUE(dspic30_initialise_data(0));
    EXPECT_EQ(chip.ram[0x0200], simulated::Chip::ram_fill);
    EXPECT_EQ(std::count(chip.ram.begin(), chip.ram.end(), simulated::Chip::ram_fill),
              std::ptrdiff_t(chip.ram.size()));
}
