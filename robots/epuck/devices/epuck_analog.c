// The analog sequencer's cycle. Each scan callback hands the finished scan
// to its driver, then chooses what the next scan converts: the choice made
// at count n is converted by the scan that finishes at count n + 1.

#include "epuck_analog.h"

// Cycle positions (§3.2): the accelerometer is converted by the scan that
// finishes at count 62, the pair's ambient level at 63 (emitter on), its lit
// level at count 4 of the next cycle (emitter off).
#define COUNT_ACCELEROMETER_FINISHED 62u
#define COUNT_AMBIENT_FINISHED       63u
#define COUNT_LIT_FINISHED                                                                         \
    ((COUNT_AMBIENT_FINISHED + EPUCK_ANALOG_PULSE_SCANS) % EPUCK_ANALOG_CYCLE)

static uint16_t source_channels(const epuck_analog *analog, epuck_analog_source source)
{
    switch (source) {
    case EPUCK_ANALOG_ACCELEROMETER: return EPUCK_ACCELEROMETER_CHANNELS;
    case EPUCK_ANALOG_PROXIMITY_AMBIENT:
    case EPUCK_ANALOG_PROXIMITY_LIT: return epuck_proximity_channels(analog->proximity);
    default: return EPUCK_MICROPHONE_CHANNELS;
    }
}

// What the scan finishing at cycle position `count` converts.
static epuck_analog_source source_at(uint8_t count)
{
    if (count == COUNT_ACCELEROMETER_FINISHED)
        return EPUCK_ANALOG_ACCELEROMETER;
    if (count == COUNT_AMBIENT_FINISHED)
        return EPUCK_ANALOG_PROXIMITY_AMBIENT;
    if (count == COUNT_LIT_FINISHED)
        return EPUCK_ANALOG_PROXIMITY_LIT;
    return EPUCK_ANALOG_MICROPHONES;
}

// The cycle position after `count` (a division costs more than this
// test, 16,384 times a second).
static uint8_t following(uint8_t count)
{
    return (uint8_t)(count + 1u == EPUCK_ANALOG_CYCLE ? 0u : count + 1u);
}

static void scan_finished(void *context, const uint16_t *values, uint8_t count)
{
    epuck_analog *analog = context;
    epuck_analog_source next;

    (void)count;
    switch (analog->scanning) {
    case EPUCK_ANALOG_ACCELEROMETER:
        epuck_accelerometer_sampled(analog->accelerometer, values);
        break;
    case EPUCK_ANALOG_PROXIMITY_AMBIENT:
        epuck_proximity_ambient_sampled(analog->proximity, values);
        break;
    case EPUCK_ANALOG_PROXIMITY_LIT: epuck_proximity_lit_sampled(analog->proximity, values); break;
    default:
        epuck_microphones_sampled(
          analog->microphones, values, analog->previous == EPUCK_ANALOG_MICROPHONES);
        break;
    }
    analog->previous = analog->scanning;
    analog->count = following(analog->count);
    next = source_at(following(analog->count));
    if (source_channels(analog, next) != source_channels(analog, analog->scanning))
        epuck_board_adc_scan_select(analog->board, source_channels(analog, next));
    analog->scanning = next;
}

// The positions of the other sources, in the order microphone_scans_from
// takes them.
typedef char
  other_sources_in_cycle_order[COUNT_LIT_FINISHED < COUNT_ACCELEROMETER_FINISHED &&
                                   COUNT_ACCELEROMETER_FINISHED + 1u == COUNT_AMBIENT_FINISHED &&
                                   COUNT_AMBIENT_FINISHED < EPUCK_ANALOG_CYCLE
                                 ? 1
                                 : -1];

// How many scans from cycle position `position` on convert the microphones
// before the next scan of another source (0 at that scan).
static uint8_t microphone_scans_from(uint8_t position)
{
    if (position <= COUNT_LIT_FINISHED)
        return (uint8_t)(COUNT_LIT_FINISHED - position);
    if (position <= COUNT_AMBIENT_FINISHED)
        return (uint8_t)(position <= COUNT_ACCELEROMETER_FINISHED
                           ? COUNT_ACCELEROMETER_FINISHED - position
                           : 0u);
    return (uint8_t)(EPUCK_ANALOG_CYCLE - position + COUNT_LIT_FINISHED);
}

// A run of scans reading the same values (a simulated board's silent
// microphones): the microphones' scans at its start, up to the next scan of
// another source, go to the microphones at once. When the run reaches that
// scan, the last microphone scan goes through scan_finished, which chooses
// what comes next; before it, the next scan converts the microphones again.
static uint16_t scans_finished(void *context, const uint16_t *values, uint8_t count, uint16_t scans)
{
    epuck_analog *analog = context;
    uint8_t first, microphone_scans;
    uint16_t run;

    if (analog->scanning != EPUCK_ANALOG_MICROPHONES) {
        scan_finished(context, values, count);
        return 1;
    }
    // The run's first scan finishes at this cycle position; the scans up
    // to the next position of another source convert the microphones.
    first = following(analog->count);
    microphone_scans = microphone_scans_from(first);
    run = scans < microphone_scans ? scans : microphone_scans;
    // The scans of the run that leave the next one to the microphones.
    scans = run == microphone_scans ? (uint16_t)(run - 1u) : run;
    if (scans > 0u) {
        uint16_t count_after = (uint16_t)(analog->count + scans);
        epuck_microphones_sampled_run(
          analog->microphones, values, analog->previous == EPUCK_ANALOG_MICROPHONES, scans);
        analog->previous = EPUCK_ANALOG_MICROPHONES;
        // A run stops short of the next cycle position of another source,
        // so it wraps round the cycle once at most.
        analog->count =
          (uint8_t)(count_after >= EPUCK_ANALOG_CYCLE ? count_after - EPUCK_ANALOG_CYCLE
                                                      : count_after);
    }
    if (scans < run)
        scan_finished(context, values, count);
    return run;
}

bool epuck_analog_start(epuck_analog *analog,
                        hal_board *board,
                        epuck_proximity *proximity,
                        epuck_accelerometer *accelerometer,
                        epuck_microphones *microphones)
{
    analog->board = board;
    analog->proximity = proximity;
    analog->accelerometer = accelerometer;
    analog->microphones = microphones;
    // As if a lit sample had just been taken: the first proximity sample is
    // then an ambient one.
    analog->count = COUNT_LIT_FINISHED;
    analog->scanning = EPUCK_ANALOG_MICROPHONES;
    analog->previous = EPUCK_ANALOG_PROXIMITY_LIT;
    if (!epuck_board_adc_scan_start(board, EPUCK_MICROPHONE_CHANNELS, scan_finished, analog))
        return false;
    epuck_board_adc_scan_runs(board, scans_finished);
    return true;
}

void epuck_analog_stop(epuck_analog *analog)
{
    uint8_t pair;

    epuck_board_adc_scan_stop(analog->board);
    for (pair = 0; pair < EPUCK_PROXIMITY_PAIRS; pair++)
        epuck_board_pin_write(analog->board, (epuck_pin)(EPUCK_PIN_IR_PULSE_0_4 + pair), false);
}
