// The chip around the instructions: interrupts (priorities, natural order,
// nesting, the CPU priority, DISI, the alternate table), traps (handled,
// hard-trap conflicts that reset, resets without handlers), the stack limit,
// an interrupted REPEAT, the NVM controller writing flash that then runs,
// the data EEPROM, modulo and bit-reversed addressing, the UART's receive
// FIFO, the watchdog and Sleep. Programs are assembled by pic30-elf-as; each
// expectation names the manual section it comes from.

#include "tests/dspic30_sim/pic30_toolchain.hpp"
#include "tools/dspic30_sim/simulator.hpp"

#include <gtest/gtest.h>

#include <array>
#include <deque>
#include <string>

namespace aseba::dspic30
{
namespace
{

constexpr uint32_t code_base = 0x100;
constexpr int step_limit = 200000;

// Vectors (research notes §8.1, fact sheet §1.7): traps 1-4, IRQ n at 8 + n.
constexpr int oscillator_failure_vector = 1;
constexpr int address_error_vector = 2;
constexpr int stack_error_vector = 3;
constexpr int t1_vector = 8 + 3;
constexpr int t2_vector = 8 + 6;
constexpr int u1rx_vector = 8 + 9;

// A program on a simulated chip: assembled at code_base, the reset vector
// leading to its label `start`.
class Machine
{
  public:
    explicit Machine(const std::string &source, std::deque<int> uart_input = {})
      : input_(std::move(uart_input))
      , simulator_({}, [this]() {
          if (input_.empty())
              return -1;
          const int b = input_.front();
          input_.pop_front();
          return b;
      })
    {
        program_ = test::assemble_program("\t.text\n" + source, code_base);
        simulator_.load(program_.words);
        const uint32_t start = symbol("start");
        cpu().program(0, 0x040000 | (start & 0xFFFE)); // GOTO start
        cpu().program(2, start >> 16);
        cpu().power_on_reset();
    }

    Cpu &cpu()
    {
        return simulator_.cpu();
    }
    Simulator &simulator()
    {
        return simulator_;
    }
    uint32_t symbol(const std::string &name) const
    {
        return program_.symbols.at(name);
    }
    // Points vector `vector` of the primary (or alternate) table at label `name`.
    void vector(int vector, const std::string &name, bool alternate = false)
    {
        cpu().program((alternate ? aivt_base : ivt_base) + 2 * static_cast<uint32_t>(vector),
                      symbol(name));
    }
    // Runs until the PC reaches label `name`; false if it never does.
    bool run_to(const std::string &name)
    {
        const uint32_t target = symbol(name);
        for (int i = 0; i < step_limit; ++i) {
            if (cpu().pc() == target)
                return true;
            cpu().run(cpu().cycles() + 1);
        }
        return false;
    }
    uint16_t data(uint16_t address)
    {
        return cpu().read_data(address);
    }
    GpioPorts &gpio()
    {
        return simulator_.gpio();
    }
    Adc &adc()
    {
        return simulator_.adc();
    }
    I2cMaster &i2c()
    {
        return simulator_.i2c();
    }

  private:
    std::deque<int> input_;
    Simulator simulator_;
    test::AssembledProgram program_;
};

// FRM Section 6 / DS70138G §8.4: an enabled flag above the CPU priority
// interrupts; entry stacks the PC and SRL, sets the CPU priority to the
// source's, and RETFIE restores them.
TEST(Interrupts, EntryAndReturn)
{
    Machine m(R"(
start:  mov #0x0008, w0
        mov w0, 0x008C          ; IEC0.T1IE
        mov #0x5000, w0
        mov w0, 0x0094          ; IPC0.T1IP = 5
        bset 0x0084, #3         ; IFS0.T1IF: the interrupt comes next
        mov #0x1111, w3
done:   bra done
isr:    mov 0x0042, w4          ; SR in the handler
        inc w5, w5
        bclr 0x0084, #3
        retfie
)");
    m.vector(t1_vector, "isr");
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.cpu().w(5), 1);
    EXPECT_EQ(m.cpu().w(4) & sr::IPL, 5 << sr::IPL_SHIFT);
    EXPECT_EQ(m.cpu().w(3), 0x1111);
    EXPECT_EQ(m.cpu().sr() & sr::IPL, 0);
    EXPECT_EQ(m.cpu().w(15), ram_start);
}

// Fact sheet §1.7 (DS70043F §6.1): at one priority the lower vector wins.
TEST(Interrupts, NaturalOrder)
{
    Machine m(R"(
start:  mov #0x0A00, w10        ; a log of handler entries
        mov #0x0048, w0
        mov w0, 0x008C          ; IEC0: T1IE and T2IE
        mov #0x4000, w0
        mov w0, 0x0094          ; IPC0: T1 at 4
        mov #0x0400, w0
        mov w0, 0x0096          ; IPC1: T2 at 4
        mov #0x0048, w0
        ior 0x0084              ; both flags at once
        nop
done:   bra done
t1:     mov #1, w0
        mov w0, [w10++]
        bclr 0x0084, #3
        retfie
t2:     mov #2, w0
        mov w0, [w10++]
        bclr 0x0084, #6
        retfie
)");
    m.vector(t1_vector, "t1");
    m.vector(t2_vector, "t2");
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.data(0x0A00), 1);
    EXPECT_EQ(m.data(0x0A02), 2);
    EXPECT_EQ(m.cpu().w(10), 0x0A04);
}

// Research notes §8.2: a higher priority preempts a running handler.
TEST(Interrupts, Nesting)
{
    Machine n(R"(
start:  mov #0x0A00, w10
        mov #0x0048, w0
        mov w0, 0x008C
        mov #0x4000, w0
        mov w0, 0x0094          ; T1 at 4
        mov #0x0600, w0
        mov w0, 0x0096          ; T2 at 6
        bset 0x0084, #3
        nop
done:   bra done
t1:     mov #1, w0
        mov w0, [w10++]
        bclr 0x0084, #3
        bset 0x0084, #6         ; T2 preempts: its entry is logged before the 3
        nop
        mov #3, w0
        mov w0, [w10++]
        retfie
t2:     mov #2, w0
        mov w0, [w10++]
        bclr 0x0084, #6
        retfie
)");
    n.vector(t1_vector, "t1");
    n.vector(t2_vector, "t2");
    ASSERT_TRUE(n.run_to("done"));
    EXPECT_EQ(n.data(0x0A00), 1);
    EXPECT_EQ(n.data(0x0A02), 2);
    EXPECT_EQ(n.data(0x0A04), 3);
}

// Research notes §8.2 (DS70043F §6.2): with INTCON1.NSTDIS every handler
// runs at level 7, so nothing nests.
TEST(Interrupts, NestingDisabled)
{
    Machine m(R"(
start:  mov #0x0A00, w10
        bset 0x0081, #7         ; INTCON1.NSTDIS
        mov #0x0048, w0
        mov w0, 0x008C
        mov #0x4000, w0
        mov w0, 0x0094
        mov #0x0600, w0
        mov w0, 0x0096
        bset 0x0084, #3
        nop
done:   bra done
t1:     mov #1, w0
        mov w0, [w10++]
        bclr 0x0084, #3
        bset 0x0084, #6
        nop
        mov #3, w0
        mov w0, [w10++]
        retfie
t2:     mov #2, w0
        mov w0, [w10++]
        bclr 0x0084, #6
        retfie
)");
    m.vector(t1_vector, "t1");
    m.vector(t2_vector, "t2");
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.data(0x0A00), 1);
    EXPECT_EQ(m.data(0x0A02), 3);
    EXPECT_EQ(m.data(0x0A04), 2);
}

// Research notes §8.2: a source is taken only above the CPU priority; DISI
// holds off levels 1-6 but not 7 (§4.7).
TEST(Interrupts, CpuPriorityAndDisi)
{
    Machine m(R"(
start:  mov #0x0048, w0
        mov w0, 0x008C
        mov #0x4000, w0
        mov w0, 0x0094          ; T1 at 4
        mov #0x00A0, w0
        mov w0, 0x0042          ; CPU priority 5
        bset 0x0084, #3
masked: nop
        nop
        clr 0x0042              ; back to 0: T1 now
low:    nop
        disi #30
        bset 0x0084, #3         ; held by DISI
held:   nop
        nop
        mov #0x0700, w0
        mov w0, 0x0096          ; T2 at 7
        bset 0x0084, #6         ; not held
seven:  nop
done:   bra done
t1:     inc w5, w5
        bclr 0x0084, #3
        retfie
t2:     inc w6, w6
        mov w5, w7              ; T1 still waiting
        bclr 0x0084, #6
        retfie
)");
    m.vector(t1_vector, "t1");
    m.vector(t2_vector, "t2");
    ASSERT_TRUE(m.run_to("masked"));
    m.cpu().run(m.cpu().cycles() + 1);
    EXPECT_EQ(m.cpu().w(5), 0) << "taken below the CPU priority";
    ASSERT_TRUE(m.run_to("low"));
    m.cpu().run(m.cpu().cycles() + 1);
    EXPECT_EQ(m.cpu().w(5), 1);
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.cpu().w(6), 1);
    EXPECT_EQ(m.cpu().w(7), 1) << "DISI did not hold level 4 while level 7 went through";
    for (int i = 0; i < 40; ++i)
        m.cpu().run(m.cpu().cycles() + 1);
    EXPECT_EQ(m.cpu().w(5), 2) << "the held interrupt after DISI";
}

// Fact sheet §1.7: INTCON2.ALTIVT selects the alternate vector table.
TEST(Interrupts, AlternateTable)
{
    Machine m(R"(
start:  bset 0x0083, #7         ; INTCON2.ALTIVT
        mov #0x0008, w0
        mov w0, 0x008C
        bset 0x0084, #3
        nop
done:   bra done
primary: mov #1, w5
        bclr 0x0084, #3
        retfie
alternate: mov #2, w5
        bclr 0x0084, #3
        retfie
)");
    m.vector(t1_vector, "primary");
    m.vector(t1_vector, "alternate", true);
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.cpu().w(5), 2);
}

// DS70178D §5.3: a word read at an odd address is an address error trap;
// the handler runs at level 13 and returns after the faulting instruction.
TEST(Traps, AddressErrorHandled)
{
    Machine m(R"(
start:  mov #0x0901, w1
        mov [w1], w2            ; odd address
        mov #0x2222, w3
done:   bra done
trap:   mov 0x0080, w4          ; INTCON1
        mov 0x0044, w6          ; CORCON: IPL3
        bclr 0x0080, #3
        inc w5, w5
        retfie
)");
    m.vector(address_error_vector, "trap");
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.cpu().w(5), 1);
    EXPECT_EQ(m.cpu().w(4) & intcon1::ADDRERR, intcon1::ADDRERR);
    EXPECT_EQ(m.cpu().w(6) & corcon::IPL3, corcon::IPL3);
    EXPECT_EQ(m.cpu().w(3), 0x2222);
    EXPECT_EQ(m.cpu().corcon() & corcon::IPL3, 0);
}

// Research notes §8.1 (DS70138G): a hard trap while one of at least its
// priority is processed resets the chip with RCON.TRAPR.
TEST(Traps, HardTrapConflictResets)
{
    Machine m(R"(
start:  mov 0x0740, w8          ; RCON after the reset
        btsc w8, #15
        bra again
        mov #0x0901, w1
        mov [w1], w2
never:  bra never
again:  bra again
trap:   mov [w1], w2            ; another address error in the handler
        retfie
)");
    m.vector(address_error_vector, "trap");
    ASSERT_TRUE(m.run_to("again"));
    EXPECT_TRUE(m.cpu().w(8) & rcon::TRAPR);
}

// Without handlers (erased vectors) a trap leads to an erased address, a
// second address error, a conflict and a reset, again and again: the run
// stops as a trap-reset storm.
TEST(Traps, NoHandlerResetStorm)
{
    Machine m(R"(
start:  mov #0x0901, w1
        mov [w1], w2
spin:   bra spin
)");
    const RunResult result = m.simulator().run(RunLimits{ 10000000, 0, false });
    EXPECT_EQ(result.outcome, Outcome::trap_reset_storm);
    ASSERT_FALSE(result.traps.empty());
    EXPECT_EQ(result.traps.front().trap, Trap::address_error);
    EXPECT_EQ(result.traps.front().pc, m.symbol("start") + 2);
}

// DS70138G §20.2.7 (the fail-safe clock monitor, FOSC.FCKSM = 00): a clock
// failure sets OSCCON.CF and takes the oscillator-failure trap, vector 1, at
// level 14 (INTCON1.OSCFAIL); with the monitor off nothing traps.
TEST(Traps, OscillatorFailureWithClockMonitor)
{
    const std::string source = R"(
start:  inc w5, w5
        bra start
trap:   mov 0x0080, w4          ; INTCON1
        mov 0x0742, w6          ; OSCCON
        mov 0x0042, w7          ; SR: the trap's level in IPL
        mov 0x0044, w8          ; CORCON: IPL3
        mov #0xCAFE, w9
        bclr 0x0080, #1
done:   bra done
)";
    constexpr uint32_t monitor_on = 0x3FE6; // FCKSM = 00, the e-puck's XT with PLL x8
    constexpr uint32_t monitor_off = 0xBFE6;
    Machine off(source);
    off.cpu().program(fosc_address, monitor_off);
    off.cpu().run(off.cpu().cycles() + 100);
    EXPECT_FALSE(off.cpu().fail_oscillator());
    off.cpu().run(off.cpu().cycles() + 100);
    EXPECT_EQ(off.data(sfr::INTCON1) & intcon1::OSCFAIL, 0);
    EXPECT_NE(off.cpu().pc(), off.symbol("done"));

    Machine on(source);
    on.vector(oscillator_failure_vector, "trap");
    on.cpu().program(fosc_address, monitor_on);
    on.cpu().run(on.cpu().cycles() + 100);
    EXPECT_TRUE(on.cpu().fail_oscillator());
    ASSERT_TRUE(on.run_to("done"));
    EXPECT_EQ(on.cpu().w(9), 0xCAFE);
    EXPECT_EQ(on.cpu().w(4) & intcon1::OSCFAIL, intcon1::OSCFAIL);
    EXPECT_EQ(on.cpu().w(6) & osccon::CF, osccon::CF);
    EXPECT_EQ(on.cpu().w(7) & sr::IPL, 6 << sr::IPL_SHIFT); // level 14 = IPL3 + 6
    EXPECT_EQ(on.cpu().w(8) & corcon::IPL3, corcon::IPL3);
}

// DS70157F §4.7.3: once SPLIM is written, a W15-based address above it is a
// stack error trap.
TEST(Traps, StackLimit)
{
    Machine m(R"(
start:  mov #0x0810, w0
        mov w0, 0x0020          ; SPLIM
        nop
        mov #0x0800, w15
more:   push w0
        bra more
trap:   mov w15, w4
        bclr 0x0080, #2
        mov #0x0900, w15        ; a stack to stop on
done:   bra done
)");
    m.vector(stack_error_vector, "trap");
    ASSERT_TRUE(m.run_to("done"));
    // The push at 0x0812 trips the limit (0x0810); the exception frame
    // takes two more words.
    EXPECT_EQ(m.cpu().w(4), 0x0818);
}

// DS70157F REPEAT: the repeated instruction can be interrupted; RA goes on
// the stack with SRL and RETFIE resumes the loop.
TEST(Loops, InterruptedRepeatResumes)
{
    Machine m(R"(
start:  mov #0x8000, w0
        mov w0, 0x020C          ; U1MODE.UARTEN, BRG = 0: a byte every 160 cycles
        mov #0x0400, w0
        mov w0, 0x020E
        mov #0x0200, w0
        mov w0, 0x008C          ; IEC0.U1RXIE
        repeat #999
        inc w1, w1
done:   bra done
rx:     mov 0x0212, w8
        inc w7, w7
        bclr 0x0084, #9
        retfie
)",
              { 'x' });
    m.vector(u1rx_vector, "rx");
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.cpu().w(1), 1000);
    EXPECT_EQ(m.cpu().w(7), 1);
    EXPECT_EQ(m.cpu().w(8), 'x');
}

// Fact sheet §1.3: a flash row is erased (NVMCON 0x4041) and programmed
// (0x4001) after 0x55, 0xAA to NVMKEY and WR; the new code then runs.
TEST(Nvm, FlashRowEraseProgramAndRun)
{
    Machine m(R"(
        .equ ROW, 0x4000
start:  clr 0x0032              ; TBLPAG
        mov #ROW, w1
        tblwtl w1, [w1]         ; selects the row
        mov #0x4041, w0
        rcall unlock            ; erase
        mov #ROW, w1
        mov #32, w4
fill:   mov #0x2349, w2         ; mov #0x1234, w9 = 0x212349
        mov #0x0021, w3
        tblwtl w2, [w1]
        tblwth w3, [w1++]
        inc w1, w1
        dec w4, w4
        bra nz, fill
        mov #ROW + 62, w1
        clr w2
        mov #0x0006, w3         ; return = 0x060000 as the last word
        tblwtl w2, [w1]
        tblwth w3, [w1]
        mov #0x4001, w0
        rcall unlock            ; program
        clr w9
        call ROW
        mov #ROW + 2, w1
        tblrdl [w1], w10
        tblrdh [w1], w11
done:   bra done
unlock: mov w0, 0x0760          ; NVMCON
        disi #5
        mov #0x55, w0
        mov w0, 0x0766
        mov #0xAA, w0
        mov w0, 0x0766
        bset 0x0761, #7         ; WR
        nop
        nop
        return
)");
    m.cpu().program(0x4000, 0x000000); // old code in the row, to be replaced
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.cpu().w(9), 0x1234);
    EXPECT_EQ(m.cpu().w(10), 0x2349);
    EXPECT_EQ(m.cpu().w(11), 0x0021);
    EXPECT_EQ(m.cpu().program_memory().read(0x403E), 0x060000u);
}

// Without the key sequence NVMCON.WR starts nothing.
TEST(Nvm, NoKeyNoWrite)
{
    Machine m(R"(
start:  clr 0x0032
        mov #0x4000, w1
        tblwtl w1, [w1]
        mov #0x4041, w0
        mov w0, 0x0760
        bset 0x0761, #7         ; WR without 0x55/0xAA
done:   bra done
)");
    m.cpu().program(0x4000, 0x123456);
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.cpu().program_memory().read(0x4000), 0x123456u);
}

// Fact sheet §1.4: a data EEPROM word write (0x4004) runs while the CPU
// goes on; the program polls NVMCON.WR.
TEST(Nvm, EepromWordWrite)
{
    Machine m(R"(
start:  mov #0x7F, w0
        mov w0, 0x0032          ; TBLPAG of the EEPROM
        mov #0xF010, w1
        mov #0xBEEF, w2
        tblwtl w2, [w1]
        mov #0x4004, w0
        mov w0, 0x0760
        disi #5
        mov #0x55, w0
        mov w0, 0x0766
        mov #0xAA, w0
        mov w0, 0x0766
        bset 0x0761, #7
        nop
        nop
wait:   inc w5, w5
        btsc 0x0761, #7
        bra wait
        tblrdl [w1], w3
done:   bra done
)");
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.cpu().w(3), 0xBEEF);
    EXPECT_GT(m.cpu().w(5), 100) << "the CPU did not run during the write";
    EXPECT_EQ(m.cpu().program_memory().read(0x7FF010), 0xBEEFu);
}

// FRM §3.3 modulo addressing: with XMODEN and XWM = W1, post-increments
// past XMODEND wrap to XMODSRT.
TEST(Addressing, Modulo)
{
    Machine m(R"(
start:  mov #0x0900, w0
        mov w0, 0x0048          ; XMODSRT
        mov #0x0907, w0
        mov w0, 0x004A          ; XMODEND: four words
        mov #0x80F1, w0
        mov w0, 0x0046          ; MODCON: XMODEN, XWM = W1, YWM/BWM off
        nop
        mov #0x0900, w1
        mov #10, w2
        repeat #5
        mov w2, [w1++]          ; six writes into four words
done:   bra done
)");
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.cpu().w(1), 0x0904);
    EXPECT_EQ(m.data(0x0908), 0) << "wrote past the buffer";
}

// FRM §3.3.2 bit-reversed addressing: with BREN, XB = 4 (an 8-word buffer)
// and BWM = W2, word writes with [W2++] go to the bit-reversed order.
TEST(Addressing, BitReversed)
{
    Machine m(R"(
start:  mov #0x8004, w0
        mov w0, 0x0050          ; XBREV: BREN, XB = 4
        mov #0x02FF, w0
        mov w0, 0x0046          ; MODCON: BWM = W2
        nop
        mov #0x0900, w2
        clr w3
        mov #8, w4
next:   mov w3, [w2++]
        inc w3, w3
        dec w4, w4
        bra nz, next
done:   bra done
)");
    ASSERT_TRUE(m.run_to("done"));
    const int order[8] = { 0, 4, 2, 6, 1, 5, 3, 7 };
    for (int i = 0; i < 8; ++i)
        EXPECT_EQ(m.data(static_cast<uint16_t>(0x0900 + 2 * order[i])), i) << "write " << i;
}

// Fact sheet §2.1: a 4-deep receive FIFO; a fifth byte unread sets OERR.
TEST(Uart, ReceiveFifoAndOverrun)
{
    Machine m(R"(
start:  mov #0x8000, w0
        mov w0, 0x020C          ; UARTEN, BRG = 0
        mov #2000, w0
wait:   dec w0, w0              ; six bytes arrive meanwhile
        bra nz, wait
        mov 0x020E, w1          ; U1STA
        mov 0x0212, w2
        mov 0x0212, w3
        mov 0x0212, w4
        mov 0x0212, w5
        mov 0x020E, w6
done:   bra done
)",
              { 'a', 'b', 'c', 'd', 'e', 'f' });
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.cpu().w(1) & 0x0003, 0x0003) << "URXDA and OERR";
    EXPECT_EQ(m.cpu().w(2), 'a');
    EXPECT_EQ(m.cpu().w(5), 'd');
    EXPECT_EQ(m.cpu().w(6) & 0x0001, 0) << "URXDA after four reads";
}

// Fact sheet §2.1 and §1.7: UART2 has UART1's registers at 0x0216-0x021E
// and its own interrupts (U2RX vector 32, IFS1/IEC1 bit 8); what it sends
// reaches UART2's host stream, not UART1's.
TEST(Uart, SecondUartHasItsOwnRegistersAndInterrupts)
{
    Machine m(R"(
start:  mov #0x8000, w0
        mov w0, 0x0216          ; U2MODE: UARTEN, BRG = 0
        mov #0x0400, w0
        mov w0, 0x0218          ; U2STA: UTXEN
        mov #'Q', w0
        mov w0, 0x021A          ; U2TXREG
        bset 0x008E, #8         ; IEC1: U2RXIE
        mov #2000, w1
wait:   dec w1, w1
        bra nz, wait
done:   bra done
rx:     mov 0x021C, w8          ; U2RXREG
        bclr 0x0086, #8         ; IFS1: U2RXIF
        retfie
)");
    std::string uart1_sent, uart2_sent;
    std::deque<int> uart2_input{ 'k' };
    m.simulator().connect_uart2([&](uint8_t b) { uart2_sent += static_cast<char>(b); },
                                [&]() {
                                    if (uart2_input.empty())
                                        return -1;
                                    const int b = uart2_input.front();
                                    uart2_input.pop_front();
                                    return b;
                                });
    m.vector(8 + 24, "rx");
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(uart2_sent, "Q");
    EXPECT_EQ(m.cpu().w(8), 'k') << "the U2RX interrupt read the byte";
    EXPECT_EQ(m.data(0x0212), 0) << "UART1's receiver saw nothing";
}

// Fact sheet §1.5: FWDTEN = 1 runs the watchdog (2 ms x prescalers); CLRWDT
// restarts it, else it resets the chip with RCON.WDTO.
TEST(Watchdog, ResetsUnlessCleared)
{
    const char *source = R"(
start:  mov 0x0740, w8
        btsc w8, #4             ; WDTO: the watchdog reset us
        bra after
        mov #20000, w0
loop:   clrwdt
        dec w0, w0
        bra nz, loop
spin:   bra spin
after:  bra after
)";
    Machine m(source);
    m.cpu().program(fwdt_address, fwdt_enable); // prescalers 1:1, 1:1
    m.cpu().power_on_reset();
    ASSERT_TRUE(m.run_to("spin")) << "a reset while CLRWDT ran";
    ASSERT_TRUE(m.run_to("after"));
    EXPECT_TRUE(m.cpu().w(8) & rcon::WDTO);
}

// Research notes §4.7: PWRSAV #0 sleeps until an enabled interrupt.
TEST(Power, SleepWakesOnInterrupt)
{
    Machine m(R"(
start:  mov #0x8000, w0
        mov w0, 0x020C
        mov #0x0200, w0
        mov w0, 0x008C          ; U1RXIE
        pwrsav #0
        mov #0x3333, w3
done:   bra done
rx:     mov 0x0212, w8
        bclr 0x0084, #9
        retfie
)",
              { 'z' });
    m.vector(u1rx_vector, "rx");
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.cpu().w(8), 'z');
    EXPECT_EQ(m.cpu().w(3), 0x3333);
    EXPECT_TRUE(m.data(sfr::RCON) & rcon::SLEEP);
}

// Fact sheet §2.2: a timer counts the instruction clock through its
// prescaler and on reaching PRx restarts from 0 with its flag set: T1 with
// PR1 = 99 at 1:1 interrupts every 100 cycles (⚠ PR + 1 counts per period,
// fact sheet).
TEST(Timers, PeriodicInterrupt)
{
    Machine m(R"(
start:  mov #99, w0
        mov w0, 0x0102          ; PR1
        mov #0x0008, w0
        mov w0, 0x008C          ; T1IE
        mov #0x8000, w0
        mov w0, 0x0104          ; T1CON: TON, 1:1
on:     mov #1000, w1
wait:   dec w1, w1
        bra nz, wait
off:    clr 0x0104
done:   bra done
t1:     inc w5, w5
        bclr 0x0084, #3
        retfie
)");
    m.vector(t1_vector, "t1");
    ASSERT_TRUE(m.run_to("on"));
    const uint64_t on = m.cpu().cycles();
    ASSERT_TRUE(m.run_to("off"));
    const uint64_t counted = m.cpu().cycles() - on;
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_NEAR(m.cpu().w(5), static_cast<double>(counted / 100), 1.0) << counted << " cycles";
}

// Fact sheet §2.2: timers 2 and 3 as one 32-bit timer (T2CON.T32); reading
// TMR2 latches TMR3 into TMR3HLD; the match flag is T3's.
TEST(Timers, ThirtyTwoBitPair)
{
    Machine m(R"(
start:  mov #0xFFF0, w0
        mov w0, 0x0106          ; TMR2 (TMR3HLD = 0: TMR3 = 0)
        mov #0x0001, w0
        mov w0, 0x010E          ; PR3:PR2 = 0x0001FFFF
        setm 0x010C
        mov #0x8008, w0
        mov w0, 0x0110          ; T2CON: TON, T32
        repeat #99
        nop
        mov 0x0106, w2          ; TMR2, latching TMR3
        mov 0x0108, w3          ; TMR3HLD
        mov 0x0084, w4          ; IFS0: no match yet
done:   bra done
)");
    ASSERT_TRUE(m.run_to("done"));
    // 0xFFF0 plus about 100 counts carried into the high word.
    EXPECT_EQ(m.cpu().w(3), 1);
    EXPECT_GT(m.cpu().w(2), 0x0040);
    EXPECT_LT(m.cpu().w(2), 0x0060);
    EXPECT_EQ(m.cpu().w(4) & 0x00C0, 0);
}

// A signal on a timer's clock pin: rising edges every 50 cycles, from cycle 25.
class Pulses : public ClockInput
{
  public:
    uint64_t rising_edges(uint64_t from, uint64_t to) const override
    {
        return until(to) - until(from);
    }
    uint64_t rising_edge(uint64_t after, uint64_t n) const override
    {
        return first + (until(after) + n - 1) * period;
    }

  private:
    static uint64_t until(uint64_t cycle) // edges at or before `cycle`
    {
        return cycle < first ? 0 : (cycle - first) / period + 1;
    }
    static constexpr uint64_t first = 25, period = 50;
};

// Fact sheet §2.2: with TCS = 1 a timer counts the rising edges of its TxCK
// pin (T4CK for Timer4), through the prescaler, and on reaching PRx sets
// its flag as with the instruction clock: PR4 = 3 at 1:1 flags on the 4th
// edge after it is started. Without a signal on the pin it does not count.
TEST(Timers, ExternalClockCountsRisingEdges)
{
    const std::string program = R"(
start:  mov #3, w0
        mov w0, 0x011A          ; PR4
        clr 0x0114              ; TMR4
        mov #0x8002, w0
        mov w0, 0x011E          ; T4CON: TON, TCS, 1:1
on:     btss 0x0086, #5         ; IFS1.T4IF
        bra on
flagged: mov 0x0114, w2         ; TMR4 just after the match: 0
        repeat #119
        nop
        mov 0x0114, w3          ; and 120 cycles later
done:   bra done
)";
    Pulses pulses;
    Machine m(program);
    m.simulator().timers().connect_clock(4, &pulses);
    ASSERT_TRUE(m.run_to("on"));
    const uint64_t on = m.cpu().cycles();
    ASSERT_TRUE(m.run_to("flagged"));
    const uint64_t fourth_edge = pulses.rising_edge(on, 4);
    EXPECT_GE(m.cpu().cycles(), fourth_edge);
    EXPECT_LE(m.cpu().cycles(), fourth_edge + 3); // the polling loop's 3 cycles
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.cpu().w(2), 0);
    // Read some 122 cycles after the match: the edges 50 and 100 cycles after it.
    EXPECT_EQ(m.cpu().w(3), 2);

    Machine unconnected(program);
    ASSERT_TRUE(unconnected.run_to("on"));
    EXPECT_FALSE(unconnected.run_to("flagged"));
}

// Fact sheet §1.7, §2.5: INT0 is RF6; INTCON2.INT0EP = 1 makes its falling
// edge set INT0IF (IFS0 bit 0), and with INT0IE the handler runs; a rising
// edge does not, until INT0EP = 0 chooses it.
TEST(Gpio, Int0OnTheEdgeIntcon2Chooses)
{
    Machine m(R"(
start:  bset 0x0082, #0         ; INTCON2.INT0EP: falling edge
        bset 0x008C, #0         ; IEC0.INT0IE
idle:   bra idle
int0:   inc w5, w5
        bclr 0x0084, #0         ; IFS0.INT0IF
        retfie
)");
    m.vector(8 + 0, "int0");
    ASSERT_TRUE(m.run_to("idle"));
    const auto settle = [&m]() {
        for (int i = 0; i < 50; ++i)
            m.cpu().run(m.cpu().cycles() + 1);
    };
    m.gpio().set_input_levels('F', 0x0040); // RF6 rises: not the chosen edge
    settle();
    EXPECT_EQ(m.cpu().w(5), 0);
    m.gpio().set_input_levels('F', 0x0000); // falls
    settle();
    EXPECT_EQ(m.cpu().w(5), 1);
    m.gpio().set_input_levels('F', 0x0000); // no edge
    m.gpio().set_input_levels('F', 0x0001); // another pin
    settle();
    EXPECT_EQ(m.cpu().w(5), 1);
    m.cpu().write_data(0x0082, 0); // INT0EP = 0: rising edge
    m.gpio().set_input_levels('F', 0x0040);
    settle();
    EXPECT_EQ(m.cpu().w(5), 2);
}

// The I/O ports as the family reference manual's I/O Ports section gives
// them, on the implemented bits of fact sheet §2.5 (p30F6014A.inc): after a
// reset every pin is an input (TRIS all ones on implemented bits, 0
// elsewhere); a PORT write goes to the latch; PORT reads the latch on
// outputs and the outside level on inputs; unimplemented bits (and the
// absent port E) read 0; a RESET instruction makes every pin an input again.
TEST(Gpio, TrisPortLatch)
{
    Machine m(R"(
start:  mov #0xFF3F, w0
        mov w0, 0x02C0          ; TRISA: RA6, RA7 outputs
        mov #0xFFFF, w0
        mov w0, 0x02C2          ; PORTA: written to LATA
written:
        bclr 0x02C4, #7         ; LATA.7
cleared:
        mov #0xFFFF, w0
        mov w0, 0x02D8          ; port E's TRIS address: nothing there
        reset
)");
    constexpr uint16_t trisa = 0x02C0, porta = 0x02C2, lata = 0x02C4;
    EXPECT_EQ(m.data(trisa), 0xF6C0) << "RA6, RA7, RA9, RA10, RA12-RA15 inputs";
    EXPECT_EQ(m.data(0x02C6), 0xFFFF) << "TRISB";
    EXPECT_EQ(m.data(0x02CC), 0xE01E) << "TRISC";
    EXPECT_EQ(m.data(0x02D2), 0xFFFF) << "TRISD";
    EXPECT_EQ(m.data(0x02DE), 0x01FF) << "TRISF";
    EXPECT_EQ(m.data(0x02E4), 0xF3CF) << "TRISG";
    m.gpio().set_input_levels('A', 0x1040); // RA12 high; RA6 driven by the chip
    ASSERT_TRUE(m.run_to("written"));
    EXPECT_EQ(m.data(trisa), 0xF600);
    EXPECT_EQ(m.data(lata), 0xF6C0) << "the latch holds the implemented bits written to PORTA";
    EXPECT_EQ(m.data(porta), 0x10C0) << "outputs RA6, RA7 from the latch, input RA12 outside";
    ASSERT_TRUE(m.run_to("cleared"));
    EXPECT_EQ(m.data(porta), 0x1040);
    EXPECT_EQ(m.gpio().pins('A'), 0x1040);
    ASSERT_TRUE(m.run_to("start")); // through the RESET instruction, before the program again
    EXPECT_EQ(m.data(0x02D8), 0) << "port E does not exist";
    EXPECT_EQ(m.data(trisa), 0xF6C0) << "inputs again after the reset";
    EXPECT_EQ(m.data(porta), 0x1040) << "RA6, an input again, shows the outside level";
}

// Fact sheet §2.3 (the 12-bit A/D section of the family reference manual):
// a manual conversion. Setting SAMP samples CH0SA's input; clearing it
// starts a conversion of 14 Tad, Tad = Tcy x (ADCS + 1) / 2 (ADCS = 19:
// 10 cycles); the result lands in ADCBUF0, DONE is set, and with SMPI = 0
// the interrupt flag (IFS0.ADIF, bit 11) with it.
TEST(Adc, ManualConversion)
{
    Machine m(R"(
start:  clr 0x02A8              ; ADPCFG: every input analog
        mov #19, w0
        mov w0, 0x02A4          ; ADCON3: ADCS = 19
        mov #5, w0
        mov w0, 0x02A6          ; ADCHS: CH0SA = AN5
        mov #0x8000, w0
        mov w0, 0x02A0          ; ADCON1: ADON, manual sampling and conversion
        bset 0x02A0, #1         ; SAMP
        nop
        nop
converting:
        bclr 0x02A0, #1         ; ending the sampling starts the conversion
wait:   btss 0x02A0, #0         ; DONE
        bra wait
converted:
        mov 0x0280, w1          ; ADCBUF0
done:   bra done
)");
    m.adc().set_input(5, 0x0ABC);
    m.adc().set_input(4, 0x0123);
    ASSERT_TRUE(m.run_to("converting"));
    const uint64_t start = m.cpu().cycles();
    ASSERT_TRUE(m.run_to("converted"));
    const uint64_t took = m.cpu().cycles() - start;
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.cpu().w(1), 0x0ABC);
    EXPECT_NEAR(static_cast<double>(took), 140.0, 6.0) << "14 Tad of 10 cycles";
    EXPECT_NE(m.data(0x0084) & 0x0800, 0) << "ADIF";
}

// Fact sheet §2.3, the e-puck library's scan: SSRC = 111 and ASAM sample
// and convert on their own, CSCNA takes the inputs of ADCSSL in ascending
// order into ADCBUF0 upward, and the interrupt comes after SMPI + 1
// conversions, every 3 x (SAMC 1 + 14) Tad = 450 cycles at ADCS = 19.
TEST(Adc, ScanWithInterrupt)
{
    Machine m(R"(
start:  clr 0x02A8              ; ADPCFG: every input analog
        mov #0x0124, w0
        mov w0, 0x02AA          ; ADCSSL: AN2, AN5, AN8
        mov #0x0113, w0
        mov w0, 0x02A4          ; ADCON3: SAMC = 1, ADCS = 19
        mov #0x0408, w0
        mov w0, 0x02A2          ; ADCON2: CSCNA, SMPI = 2
        mov #0x0800, w0
        mov w0, 0x008C          ; IEC0.ADIE
        mov #0x00E4, w0
        mov w0, 0x02A0          ; ADCON1: SSRC = 111, ASAM
        bset 0x02A0, #15        ; ADON
on:     mov #3000, w1
wait:   dec w1, w1
        bra nz, wait
off:    clr 0x02A0
done:   bra done
adc:    inc w5, w5
        mov 0x0280, w8
        mov 0x0282, w9
        mov 0x0284, w10
        bclr 0x0084, #11
        retfie
)");
    m.vector(8 + 11, "adc");
    m.adc().set_input(2, 100);
    m.adc().set_input(5, 200);
    m.adc().set_input(8, 300);
    m.adc().set_input(3, 999); // not scanned
    ASSERT_TRUE(m.run_to("on"));
    const uint64_t on = m.cpu().cycles();
    ASSERT_TRUE(m.run_to("off"));
    const uint64_t counted = m.cpu().cycles() - on;
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_EQ(m.cpu().w(8), 100);
    EXPECT_EQ(m.cpu().w(9), 200);
    EXPECT_EQ(m.cpu().w(10), 300);
    EXPECT_NEAR(m.cpu().w(5), static_cast<double>(counted) / 450.0, 1.0) << counted << " cycles";
}

// A slave with 256 registers as I2C register devices work (the e-puck's
// camera and accelerometer): after its address for writing, the first byte
// is the register, the next ones written from it upward; a read returns the
// registers from it upward.
class RegisterDevice : public I2cDevice
{
  public:
    std::array<uint8_t, 256> registers{};
    int starts = 0, stops = 0;

    void start(bool reading) override
    {
        ++starts;
        pointer_set_ = reading;
    }
    bool receive(uint8_t byte) override
    {
        if (!pointer_set_) {
            pointer_ = byte;
            pointer_set_ = true;
        } else {
            registers[pointer_++] = byte;
        }
        return true;
    }
    uint8_t send() override
    {
        return registers[pointer_++];
    }
    void stop() override
    {
        ++stops;
    }

  private:
    uint8_t pointer_ = 0;
    bool pointer_set_ = false;
};

// Fact sheet §2.4 (the family reference manual's I2C section, master mode):
// each step started by an I2CCON bit, or by writing I2CTRN, ends with the
// bit (or TBF and TRSTAT) cleared and the MI2C flag (IFS0 bit 14) set; a
// byte sent takes 9 bit times with its acknowledge; ACKSTAT tells whether
// the slave acknowledged. The program writes two registers, reads them
// back with a repeated start, then addresses a device that is not there.
TEST(I2c, MasterWritesReadsAndMeetsANack)
{
    Machine m(R"(
        ; w8 = I2CCON 0x0206, w9 = I2CSTAT 0x0208; each step then waits for MI2C
start:  mov #9, w0
        mov w0, 0x0204          ; I2CBRG = 9: a bit time of 10 cycles
        mov #0x8000, w0
        mov w0, 0x0206          ; I2CEN
        call start_bit
        mov #0x3C, w0           ; device 0x1E, write
        call send
        mov #0x10, w0           ; register 0x10
        call send
        mov #0xA5, w0
        call send
        mov #0x5A, w0
        call send
        call stop_bit
        call start_bit
        mov #0x3C, w0
        call send
        mov #0x10, w0
        call send
        bset 0x0206, #1         ; RSEN
        call wait_flag
        mov #0x3D, w0           ; device 0x1E, read
        call send
        bset 0x0206, #3         ; RCEN
        call wait_flag
        mov 0x0200, w4          ; I2CRCV
        bclr 0x0206, #5         ; ACKDT = 0: acknowledge
        bset 0x0206, #4         ; ACKEN
        call wait_flag
        bset 0x0206, #3
        call wait_flag
        mov 0x0200, w5
        bset 0x0206, #5         ; NACK the last byte
        bset 0x0206, #4
        call wait_flag
        call stop_bit
        call start_bit
timed:  mov #0x90, w0           ; device 0x48: nobody there
        call send
nacked: mov 0x0208, w6          ; I2CSTAT after it
        call stop_bit
done:   bra done
start_bit:
        bset 0x0206, #0         ; SEN
        bra wait_flag
stop_bit:
        bset 0x0206, #2         ; PEN
        bra wait_flag
send:   mov w0, 0x0202          ; I2CTRN
wait_flag:
        btss 0x0084, #14        ; IFS0.MI2CIF
        bra wait_flag
        bclr 0x0084, #14
        inc w7, w7              ; steps completed
        return
)");
    RegisterDevice device;
    m.i2c().connect(0x1E, device);
    ASSERT_TRUE(m.run_to("timed"));
    EXPECT_EQ(device.registers[0x10], 0xA5);
    EXPECT_EQ(device.registers[0x11], 0x5A);
    EXPECT_EQ(m.cpu().w(4), 0xA5) << "read back with a repeated start";
    EXPECT_EQ(m.cpu().w(5), 0x5A);
    EXPECT_EQ(device.starts, 3);
    EXPECT_EQ(device.stops, 2);
    const uint64_t before = m.cpu().cycles();
    ASSERT_TRUE(m.run_to("nacked"));
    EXPECT_NEAR(static_cast<double>(m.cpu().cycles() - before), 90.0, 12.0)
      << "a byte and its acknowledge: 9 bit times of 10 cycles";
    ASSERT_TRUE(m.run_to("done"));
    EXPECT_NE(m.cpu().w(6) & 0x8000, 0) << "ACKSTAT: not acknowledged";
    EXPECT_EQ(m.cpu().w(6) & 0x4001, 0) << "TRSTAT and TBF clear";
    EXPECT_EQ(m.cpu().w(7), 19) << "every step raised MI2C";
    EXPECT_EQ(m.data(0x0206) & 0x001F, 0) << "every step bit cleared";
}

} // namespace
} // namespace aseba::dspic30
