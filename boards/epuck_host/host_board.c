// The host board's clock and scheduler, its link (a receive ring and an
// output callback), interrupt masking, reset and idle.

#include "host_board.h"

#include <string.h>

#define MILLISECONDS_PER_SECOND 1000u
#define MICROSECONDS_PER_SECOND 1000000u

void host_board_init(hal_board *board,
                     void (*link_output)(void *context, const uint8_t *bytes, uint16_t count),
                     void *link_context)
{
    uint32_t i;

    memset(board, 0, sizeof *board);
    board->link_output = link_output;
    board->link_context = link_context;
    board->world = host_world_flat();
    board->power_cut_at = HOST_NO_POWER_CUT;
    board->inputs_watched_at = board->configuration_changes - 1u;
    board->first_timer_at = board->configuration_changes - 1u;
    for (i = 0; i < HOST_EEPROM_WORDS; i++)
        board->eeprom[i] = HOST_EEPROM_ERASED;
    for (i = 0; i < HOST_FLASH_WORDS; i++)
        board->flash[i] = HAL_FLASH_ERASED;
}

void host_board_set_world(hal_board *board, const host_world *world)
{
    uint16_t pin;

    board->world = world;
    // Whether it foresees input changes is the new world's to say.
    board->inputs_watched_at = board->configuration_changes - 1u;
    for (pin = EPUCK_PIN_FIRST_INPUT; pin < EPUCK_PIN_COUNT; pin++)
        board->last_input[pin] = world->pin_read(world->context, (epuck_pin)pin, board->cycles);
}

uint64_t host_board_cycles(const hal_board *board)
{
    return board->cycles;
}

// The values of the scanned channels at the board's time, into `values`;
// returns how many.
static uint8_t read_scan(hal_board *board, uint16_t *values)
{
    const host_world *world = board->world;
    uint8_t count = 0;
    uint8_t channel;
    uint16_t mask;

    if (world->adc_read_channels) {
        world->adc_read_channels(world->context, board->adc_scan_mask, board->cycles, values);
        count = board->adc_scan_channels;
    } else {
        // Only the mask's channels, lowest first: a scan takes 2 to 6 of 16.
        for (mask = board->adc_scan_mask; mask != 0; mask = (uint16_t)(mask & (mask - 1u))) {
            channel = (uint8_t)__builtin_ctz(mask);
            values[count++] = world->adc_read(world->context, channel, board->cycles);
        }
    }
    return count;
}

// Runs the ADC scan due now, and with it the later scans due up to `until`
// that the firmware takes at once (the board's time is then the last
// one's). Here rather than beside the other peripherals: the scheduler
// calls it for most of its events, so that it inlines.
static void run_adc_scans(hal_board *board, uint64_t until)
{
    const host_world *world = board->world;
    uint16_t values[EPUCK_ADC_SCAN_MAX_CHANNELS];
    uint8_t count = read_scan(board, values);
    uint64_t due = (until - board->adc_next_due) / HOST_ADC_SCAN_PERIOD_CYCLES + 1u;
    uint16_t taken;

    if (due > 1u && board->adc_scan_run_callback && world->adc_channels_steady &&
        world->adc_channels_steady(world->context, board->adc_scan_mask)) {
        // The scans due up to `until` all read what this one reads.
        taken = board->adc_scan_run_callback(
          board->adc_scan_context, values, count, (uint16_t)(due < UINT16_MAX ? due : UINT16_MAX));
        if (taken < 1u)
            taken = 1u;
        board->cycles = board->adc_next_due + (uint64_t)(taken - 1u) * HOST_ADC_SCAN_PERIOD_CYCLES;
        board->adc_next_due = board->cycles + HOST_ADC_SCAN_PERIOD_CYCLES;
        return;
    }
    board->adc_next_due += HOST_ADC_SCAN_PERIOD_CYCLES;
    if (board->adc_scan_callback)
        board->adc_scan_callback(board->adc_scan_context, values, count);
}

static bool any_input_watched(const hal_board *board)
{
    uint16_t pin;

    for (pin = EPUCK_PIN_FIRST_INPUT; pin < EPUCK_PIN_COUNT; pin++)
        if (board->edge_callback[pin])
            return true;
    return false;
}

// What falls due next, other than an ADC scan: a timer, or a change of the
// inputs.
#define EVENT_NONE         (-1)
#define EVENT_INPUT_CHANGE EPUCK_TIMER_COUNT

// The running timer due first (the first of a tie), into the board's
// first_timer and first_timer_due.
static void find_first_timer(hal_board *board)
{
    int16_t chosen = EVENT_NONE;
    uint64_t due = 0;
    int16_t i;

    for (i = 0; i < EPUCK_TIMER_COUNT; i++) {
        const host_periodic *timer = &board->timers[i];
        if (timer->running && (chosen < 0 || timer->next_due < due)) {
            chosen = i;
            due = timer->next_due;
        }
    }
    board->first_timer = chosen;
    board->first_timer_due = due;
    board->first_timer_at = board->configuration_changes;
}

// The earliest timer or input change at or before `until` (EVENT_NONE,
// EVENT_INPUT_CHANGE, else a timer), its cycle in `due`. `*input_change`,
// when `*input_known`, is the world's answer to an earlier question: it
// holds until the clock reaches it (host_world.h), then the world is asked
// again.
static int16_t next_timer_or_input(hal_board *board,
                                   uint64_t until,
                                   bool inputs_watched,
                                   uint64_t *due,
                                   uint64_t *input_change,
                                   bool *input_known)
{
    int16_t chosen = EVENT_NONE;

    if (board->first_timer_at != board->configuration_changes)
        find_first_timer(board);
    if (board->first_timer >= 0 && board->first_timer_due <= until) {
        chosen = board->first_timer;
        *due = board->first_timer_due;
    }
    if (inputs_watched) {
        if (!*input_known || *input_change <= board->cycles) {
            *input_change = board->world->next_input_change(board->world->context, board->cycles);
            *input_known = true;
        }
        if (*input_change > board->cycles && *input_change <= until &&
            (chosen < 0 || *input_change < *due)) {
            chosen = EVENT_INPUT_CHANGE;
            *due = *input_change;
        }
    }
    return chosen;
}

void host_board_advance(hal_board *board, uint64_t cycles)
{
    uint64_t until = board->cycles + cycles;
    uint64_t input_change = 0;
    bool input_known = false;
    uint16_t pin;

    for (;;) {
        uint64_t due = 0;
        uint64_t scans_until;
        uint64_t run_until;
        uint32_t changes = board->configuration_changes;
        int16_t event;

        // Whether an input is watched, worked out again only when a
        // peripheral started or stopped: the scheduler asks at every event.
        if (changes != board->inputs_watched_at) {
            board->inputs_watched = board->world->next_input_change && any_input_watched(board);
            board->inputs_watched_at = changes;
        }
        event = next_timer_or_input(
          board, until, board->inputs_watched, &due, &input_change, &input_known);
        scans_until = event == EVENT_NONE ? until : due;
        // A run of unchanging scans goes to the firmware before the timers
        // due during it (epuck_adc_scan_run_callback): a motor's steps
        // would otherwise cut the microphones' runs a thousand times a
        // second. Input changes still end it.
        run_until = scans_until;
        if (event != EVENT_NONE && event != EVENT_INPUT_CHANGE)
            run_until = board->inputs_watched && input_change < until ? input_change : until;

        // The ADC scans up to the next other event, the one at the same
        // cycle included (a scan goes first), in a row: at 16,384 a second
        // they are most of the events. A callback that starts or stops a
        // peripheral ends the row, so that the next event is chosen again.
        while (board->adc_scan_mask != 0 && board->adc_next_due <= scans_until) {
            board->cycles = board->adc_next_due;
            run_adc_scans(board, run_until);
            if (board->configuration_changes != changes)
                break;
        }
        if (board->configuration_changes != changes)
            continue;
        if (event == EVENT_NONE)
            break;
        // A scan at the cycle of the input change hides it: the world is
        // asked again for a change after that cycle.
        if (event == EVENT_INPUT_CHANGE && board->cycles >= due)
            continue;
        // The time goes back to the timer's when a run of scans went past it.
        board->cycles = due;
        // Firmware code other than the scan's ran: ask the world again,
        // unless its answers do not depend on the firmware.
        if (!board->world->input_changes_fixed)
            input_known = false;
        if (event == EVENT_INPUT_CHANGE) {
            for (pin = EPUCK_PIN_FIRST_INPUT; pin < EPUCK_PIN_COUNT; pin++)
                if (board->edge_callback[pin])
                    host_board_input_changed(board, (epuck_pin)pin);
        } else {
            host_periodic *timer = &board->timers[event];
            timer->next_due += timer->period;
            find_first_timer(board);
            if (timer->callback)
                timer->callback(timer->context);
        }
    }
    board->cycles = until;
}

void host_board_set_time(hal_board *board, uint32_t milliseconds)
{
    uint32_t ahead = milliseconds - hal_milliseconds(board);
    uint64_t target;

    if ((int32_t)ahead <= 0)
        return;
    // The cycle at which hal_milliseconds reaches `milliseconds`.
    target = ((uint64_t)board->cycles * MILLISECONDS_PER_SECOND / HOST_CYCLES_PER_SECOND + ahead) *
             HOST_CYCLES_PER_SECOND;
    target = (target + MILLISECONDS_PER_SECOND - 1u) / MILLISECONDS_PER_SECOND;
    host_board_advance(board, target - board->cycles);
}

uint32_t hal_milliseconds(hal_board *board)
{
    return (uint32_t)(board->cycles * MILLISECONDS_PER_SECOND / HOST_CYCLES_PER_SECOND);
}

void hal_delay_microseconds(hal_board *board, uint16_t microseconds)
{
    // Simulated time moves only when the host says so.
    (void)board;
    (void)microseconds;
}

uint16_t host_board_link_room(const hal_board *board)
{
    return (uint16_t)(HAL_LINK_RECEIVE_CAPACITY - board->receive_count);
}

bool host_board_link_deliver(hal_board *board, const uint8_t *bytes, uint16_t count)
{
    uint16_t end;
    uint16_t first;

    if (count > host_board_link_room(board))
        return false;
    if (count == 0)
        return true;
    // Into the ring in at most two pieces: up to its end, then from its start.
    end = (uint16_t)((board->receive_start + board->receive_count) % HAL_LINK_RECEIVE_CAPACITY);
    first = (uint16_t)(HAL_LINK_RECEIVE_CAPACITY - end);
    if (first > count)
        first = count;
    memcpy(board->receive + end, bytes, first);
    // Most pieces end before the ring does: spare the second call then.
    if (count > first)
        memcpy(board->receive, bytes + first, (size_t)(count - first));
    board->receive_count = (uint16_t)(board->receive_count + count);
    return true;
}

// Apart from hal_link_receive, so that the main loop's look at an empty
// ring (every millisecond) saves no registers for the copy.
__attribute__((noinline)) static uint16_t take_received(hal_board *board,
                                                        uint8_t *bytes,
                                                        uint16_t count)
{
    uint16_t first = (uint16_t)(HAL_LINK_RECEIVE_CAPACITY - board->receive_start);

    // Out of the ring in at most two pieces, as they went in.
    if (first > count)
        first = count;
    memcpy(bytes, board->receive + board->receive_start, first);
    if (count > first)
        memcpy(bytes + first, board->receive, (size_t)(count - first));
    board->receive_start = (uint16_t)((board->receive_start + count) % HAL_LINK_RECEIVE_CAPACITY);
    board->receive_count = (uint16_t)(board->receive_count - count);
    return count;
}

uint16_t hal_link_receive(hal_board *board, uint8_t *bytes, uint16_t capacity)
{
    uint16_t count = capacity < board->receive_count ? capacity : board->receive_count;

    if (count == 0)
        return 0;
    return take_received(board, bytes, count);
}

uint16_t hal_link_send(hal_board *board, const uint8_t *bytes, uint16_t count)
{
    // An infinitely fast UART: the bytes leave at once.
    if (board->link_output)
        board->link_output(board->link_context, bytes, count);
    return count;
}

uint16_t hal_link_send_room(hal_board *board)
{
    (void)board;
    return HAL_LINK_TRANSMIT_CAPACITY;
}

bool epuck_board_timer_start(hal_board *board,
                             epuck_timer timer,
                             uint32_t period_microseconds,
                             epuck_callback callback,
                             void *context)
{
    host_periodic *slot;
    uint64_t period;

    if ((uint16_t)timer >= EPUCK_TIMER_COUNT || period_microseconds < EPUCK_TIMER_MIN_PERIOD_US ||
        period_microseconds > EPUCK_TIMER_MAX_PERIOD_US)
        return false;
    // The period in cycles, rounded to the nearest.
    period =
      ((uint64_t)period_microseconds * HOST_CYCLES_PER_SECOND + MICROSECONDS_PER_SECOND / 2u) /
      MICROSECONDS_PER_SECOND;
    slot = &board->timers[timer];
    slot->callback = callback;
    slot->context = context;
    slot->period = period;
    slot->next_due = board->cycles + period;
    slot->running = true;
    board->configuration_changes++;
    return true;
}

void epuck_board_timer_stop(hal_board *board, epuck_timer timer)
{
    if ((uint16_t)timer < EPUCK_TIMER_COUNT)
        board->timers[timer].running = false;
    board->configuration_changes++;
}

hal_critical_state hal_critical_enter(hal_board *board)
{
    // Callbacks run only inside host_board_advance, never in the middle of
    // firmware code, so the depth is bookkeeping.
    return board->critical_depth++;
}

void hal_critical_leave(hal_board *board, hal_critical_state state)
{
    board->critical_depth = state;
}

void hal_reset(hal_board *board)
{
    board->reset_requested = true;
}

void host_board_reset(hal_board *board)
{
    // A reset stops every peripheral and forgets what the UART held; the
    // clock, the world, the link's wiring and the memories are not the
    // chip's to lose.
    memset(board->timers, 0, sizeof board->timers);
    board->adc_scan_callback = 0;
    board->adc_scan_run_callback = 0;
    board->adc_scan_context = 0;
    board->adc_scan_mask = 0;
    memset(board->outputs, 0, sizeof board->outputs);
    memset(board->edge_callback, 0, sizeof board->edge_callback);
    memset(board->edge_context, 0, sizeof board->edge_context);
    board->camera_bytes = 0;
    board->receive_start = 0;
    board->receive_count = 0;
    board->critical_depth = 0;
    board->reset_requested = false;
    board->configuration_changes++;
}

bool host_board_take_reset(hal_board *board)
{
    bool requested = board->reset_requested;
    board->reset_requested = false;
    return requested;
}

void hal_idle(hal_board *board)
{
    // The host scheduler decides when a board runs again.
    (void)board;
}
