// Traps, interrupts, resets and the work between instructions: the
// priority arbitration of the dsPIC30F (traps by vector order, IRQs by
// their IPC priority then by natural order), exception entry and RETFIE,
// hard-trap conflicts that reset the chip, DISI, Sleep/Idle, the watchdog,
// and the peripherals' events (research notes §8, DS70157 §2.12).

#include "tools/dspic30_sim/cpu_inline.hpp"

#include <cstdio>

namespace aseba::dspic30
{
namespace
{

constexpr int irq_count = 54; // IRQ 0..53 (vectors 8..61)
constexpr int first_irq_vector = 8;
constexpr int ipc_field_bits = 3;
constexpr int ipc_fields_per_register = 4;
constexpr int user_level_max = 7;         // DISI holds off levels 1..6
constexpr int trap_level_base = 15;       // trap vector k has priority 15 - k
constexpr int exception_entry_cycles = 4; // ⚠ FRM §6 latency not read
constexpr uint16_t ipc_reset_value = 0x4444;
constexpr uint16_t rcon_reset_keep = rcon::POR; // bits of RCON a later reset leaves alone
constexpr uint16_t srl_bits = 0x00FF;
constexpr uint16_t stacked_ipl3 = 1u << 7;
constexpr uint16_t stacked_pc_high = 0x007F;

int trap_level(Trap trap)
{
    return trap_level_base - static_cast<int>(trap);
}

bool hard_trap(Trap trap)
{
    return trap != Trap::math_error;
}

uint16_t trap_flag(Trap trap)
{
    switch (trap) {
    case Trap::oscillator_failure: return intcon1::OSCFAIL;
    case Trap::address_error: return intcon1::ADDRERR;
    case Trap::stack_error: return intcon1::STKERR;
    case Trap::math_error: return intcon1::MATHERR;
    }
    return 0;
}

} // namespace

int Cpu::cpu_priority() const
{
    return ((corcon_ & corcon::IPL3) ? 8 : 0) | ((sr_ & sr::IPL) >> sr::IPL_SHIFT);
}

void Cpu::raise_interrupt(int irq)
{
    sfr_[sfr::IFS0 / 2 + irq / 16] |= static_cast<uint16_t>(1u << (irq % 16));
    recompute_interrupts();
}

bool Cpu::interrupt_flag(int irq) const
{
    return (sfr_[sfr::IFS0 / 2 + irq / 16] >> (irq % 16)) & 1;
}

void Cpu::recompute_interrupts()
{
    irq_level_ = 0;
    irq_number_ = -1;
    for (int irq = 0; irq < irq_count; ++irq) {
        const int word = irq / 16;
        const uint16_t bit_mask = static_cast<uint16_t>(1u << (irq % 16));
        if (!(sfr_[sfr::IFS0 / 2 + word] & sfr_[sfr::IEC0 / 2 + word] & bit_mask))
            continue;
        const uint16_t ipc = sfr_[sfr::IPC0 / 2 + irq / ipc_fields_per_register];
        const int level = (ipc >> (ipc_field_bits + 1) * (irq % ipc_fields_per_register)) & 7;
        if (level > irq_level_) {
            irq_level_ = level;
            irq_number_ = irq;
        }
    }
    next_event_ = 0; // service() decides whether anything is taken
}

void Cpu::raise_trap(Trap trap, std::string cause)
{
    if (trap_cause_.empty()) {
        trap_cause_ = std::move(cause);
        trap_pc_ = current_pc_;
        trap_registers_ = register_summary();
    }
    if (hard_trap(trap) && cpu_priority() >= trap_level(trap)) {
        // A hard trap while one of at least its priority is being
        // processed: the chip resets (RCON.TRAPR).
        trap_pending_ |= static_cast<uint8_t>(1u << 7);
        trap_pending_ |= static_cast<uint8_t>(1u << static_cast<int>(trap));
    } else {
        trap_pending_ |= static_cast<uint8_t>(1u << static_cast<int>(trap));
    }
    sfr_[sfr::INTCON1 / 2] |= trap_flag(trap);
    next_event_ = 0;
}

bool Cpu::fail_oscillator()
{
    const uint16_t fosc = static_cast<uint16_t>(program_.read(fosc_address));
    if (fosc & fosc_fcksm)
        return false;
    // DS70138G §20.2.7: CF set, OSWEN cleared, the trap raised. ⚠ The switch
    // to the FRC oscillator (COSC) is not modelled: cycles keep their length.
    uint16_t &osccon_value = sfr_[sfr::OSCCON / 2];
    osccon_value = static_cast<uint16_t>((osccon_value | osccon::CF) & ~osccon::OSWEN);
    raise_trap(Trap::oscillator_failure, "oscillator failure (fail-safe clock monitor)");
    return true;
}

void Cpu::take_exception(int vector, int level)
{
    const uint32_t return_pc = pc_;
    const uint16_t stacked = static_cast<uint16_t>(((sr_ & srl_bits) << 8) |
                                                   ((corcon_ & corcon::IPL3) ? stacked_ipl3 : 0) |
                                                   ((return_pc >> 16) & stacked_pc_high));
    // The frame itself is not checked against SPLIM: a stack error trap
    // must be able to enter its handler (⚠ the manuals read do not say).
    for (const uint16_t word : { static_cast<uint16_t>(return_pc), stacked }) {
        write_word(w_[15], word);
        w_[15] = static_cast<uint16_t>(w_[15] + 2);
    }
    // The REPEAT in progress is suspended (RA is on the stack).
    sr_ = static_cast<uint16_t>(sr_ & ~sr::RA);
    watch_pc_ = (sr_ & sr::DA) ? doend_ : no_watch;
    if (level >= 8) {
        corcon_ |= corcon::IPL3;
        sr_ = static_cast<uint16_t>((sr_ & ~sr::IPL) | ((level - 8) << sr::IPL_SHIFT));
    } else {
        const bool nesting_off = sfr_[sfr::INTCON1 / 2] & intcon1::NSTDIS;
        const int ipl = nesting_off ? user_level_max : level;
        sr_ = static_cast<uint16_t>((sr_ & ~sr::IPL) | (ipl << sr::IPL_SHIFT));
    }
    const bool alternate = sfr_[sfr::INTCON2 / 2] & intcon2::ALTIVT;
    const uint32_t slot = (alternate ? aivt_base : ivt_base) + 2 * static_cast<uint32_t>(vector);
    pc_ = program_.read(slot) & pc_mask;
    cycles_ += exception_entry_cycles;
    sleeping_ = false;
}

void Cpu::return_from_interrupt()
{
    const uint16_t stacked = pop_word();
    const uint16_t low = pop_word();
    sr_ = static_cast<uint16_t>((sr_ & ~srl_bits) | (stacked >> 8));
    if (stacked & stacked_ipl3)
        corcon_ |= corcon::IPL3;
    else
        corcon_ = static_cast<uint16_t>(corcon_ & ~corcon::IPL3);
    pc_ = ((static_cast<uint32_t>(stacked & stacked_pc_high) << 16) | low) & pc_mask;
    if (sr_ & sr::RA) {
        repeat_pc_ = pc_;
        watch_pc_ = pc_;
    }
    recompute_interrupts();
}

void Cpu::device_reset(uint16_t rcon_cause)
{
    w_.fill(0);
    w_[15] = ram_start;
    pc_ = 0;
    sr_ = 0;
    corcon_ = corcon::RESET_VALUE;
    acc_.fill(0);
    splim_ = 0;
    splim_written_ = false;
    tblpag_ = psvpag_ = 0;
    rcount_ = dcount_ = 0;
    dostart_ = doend_ = 0;
    modcon_ = xmodsrt_ = xmodend_ = ymodsrt_ = ymodend_ = xbrev_ = 0;
    special_addressing_ = false;
    watch_pc_ = no_watch;
    const uint16_t rcon = sfr_[sfr::RCON / 2];
    sfr_.fill(0);
    for (uint16_t a = sfr::IPC0; a < sfr::IPC_END; a += 2)
        sfr_[a / 2] = ipc_reset_value;
    sfr_[sfr::RCON / 2] = static_cast<uint16_t>((rcon & rcon_reset_keep) | rcon_cause);
    trap_pending_ = 0;
    irq_level_ = 0;
    irq_number_ = -1;
    disi_end_ = 0;
    sleeping_ = false;
    nvmcon_ = nvmadr_ = nvmadru_ = 0;
    nvm_key_state_ = 0;
    nvm_done_at_ = never;
    latches_.fill(erased_word);
    latch_written_.fill(false);
    for (Peripheral *p : peripherals_)
        p->reset();
    restart_watchdog();
    next_event_ = 0;
}

void Cpu::power_on_reset()
{
    sfr_[sfr::RCON / 2] = 0;
    device_reset(rcon::POR);
    trap_resets_ = 0;
    cycles_ = 0;
}

void Cpu::trap_reset(Trap trap)
{
    if (trap_observer_)
        trap_observer_(TrapRecord{ trap, trap_pc_, cycles_, true, trap_cause_, trap_registers_ });
    trap_cause_.clear();
    trap_resets_ = (cycles_ - last_trap_reset_ < storm_window) ? trap_resets_ + 1 : 1;
    last_trap_reset_ = cycles_;
    device_reset(rcon::TRAPR);
}

void Cpu::restart_watchdog()
{
    const uint16_t fwdt = static_cast<uint16_t>(program_.read(fwdt_address));
    const bool enabled = (fwdt & fwdt_enable) || (sfr_[sfr::RCON / 2] & rcon::SWDTEN);
    if (!enabled) {
        watchdog_at_ = never;
        return;
    }
    static constexpr uint64_t prescaler_a[4] = { 1, 8, 64, 512 };
    const uint64_t period =
      watchdog_base_cycles * prescaler_a[(fwdt >> 4) & 3] * ((fwdt & 0xF) + 1);
    watchdog_at_ = cycles_ + period;
}

bool Cpu::service(uint64_t cycle_limit, StopReason &reason)
{
    if (stop_requested_) {
        stop_requested_ = false;
        reason = StopReason::requested;
        next_event_ = 0;
        return false;
    }
    for (Peripheral *p : peripherals_)
        if (p->next_event() <= cycles_)
            p->advance(cycles_);
    if (nvm_done_at_ <= cycles_)
        nvm_finish();
    if (watchdog_at_ <= cycles_) {
        if (sleeping_) {
            sleeping_ = false;
            sfr_[sfr::RCON / 2] |= rcon::WDTO;
            restart_watchdog();
        } else {
            device_reset(rcon::WDTO);
        }
    }

    // Traps first, by vector order; a hard-trap conflict resets the chip.
    if (trap_pending_ & (1u << 7)) {
        Trap trap = Trap::math_error;
        for (int t = 1; t <= 4; ++t)
            if (trap_pending_ & (1u << t)) {
                trap = static_cast<Trap>(t);
                break;
            }
        trap_reset(trap);
        if (trap_resets_ >= storm_resets) {
            reason = StopReason::trap_reset_storm;
            return false;
        }
    } else if (trap_pending_) {
        for (int t = 1; t <= 4; ++t) {
            const Trap trap = static_cast<Trap>(t);
            if (!(trap_pending_ & (1u << t)) || trap_level(trap) <= cpu_priority())
                continue;
            trap_pending_ = static_cast<uint8_t>(trap_pending_ & ~(1u << t));
            if (trap_observer_)
                trap_observer_(
                  TrapRecord{ trap, trap_pc_, cycles_, false, trap_cause_, trap_registers_ });
            trap_cause_.clear();
            take_exception(t, trap_level(trap));
            break;
        }
    }
    if (!trap_pending_)
        trap_cause_.clear();

    // Then the highest pending interrupt above the CPU's priority.
    const bool disi_active = cycles_ < disi_end_;
    if (irq_level_ > 0) {
        const bool held = disi_active && irq_level_ < user_level_max;
        if (irq_level_ > cpu_priority() && !held) {
            take_exception(first_irq_vector + irq_number_, irq_level_);
            recompute_interrupts();
        } else if (sleeping_) {
            sleeping_ = false; // an enabled interrupt wakes the chip; execution goes on
        }
    }

    // Asleep: time passes until something happens.
    if (sleeping_) {
        if (cycles_ >= cycle_limit) {
            reason = StopReason::cycle_limit;
            next_event_ = 0;
            return false;
        }
        uint64_t wake = std::min(cycle_limit, watchdog_at_);
        for (Peripheral *p : peripherals_)
            wake = std::min(wake, p->next_event());
        wake = std::min(wake, nvm_done_at_);
        if (wake == never) { // nothing will ever wake the chip
            reason = StopReason::cycle_limit;
            next_event_ = 0;
            return false;
        }
        cycles_ = std::max(cycles_, wake);
        next_event_ = cycles_;
        return true;
    }

    if (cycles_ >= cycle_limit) {
        reason = StopReason::cycle_limit;
        next_event_ = 0;
        return false;
    }
    uint64_t next = std::min(cycle_limit, watchdog_at_);
    for (Peripheral *p : peripherals_)
        next = std::min(next, p->next_event());
    next = std::min(next, nvm_done_at_);
    if (trap_pending_ ||
        (irq_level_ > cpu_priority() && disi_active && irq_level_ < user_level_max))
        next = std::min(next, trap_pending_ ? cycles_ + 1 : disi_end_);
    next_event_ = next;
    return true;
}

} // namespace aseba::dspic30
