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
    analog->count = (uint8_t)((analog->count + 1u) % EPUCK_ANALOG_CYCLE);
    next = source_at((uint8_t)((analog->count + 1u) % EPUCK_ANALOG_CYCLE));
    if (source_channels(analog, next) != source_channels(analog, analog->scanning))
        epuck_board_adc_scan_select(analog->board, source_channels(analog, next));
    analog->scanning = next;
}

// How many scans from cycle position `position` on come before position
// `other` (0 for `other` itself).
static uint8_t scans_before(uint8_t position, uint8_t other)
{
    return (uint8_t)((other + EPUCK_ANALOG_CYCLE - position) % EPUCK_ANALOG_CYCLE);
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
    first = (uint8_t)((analog->count + 1u) % EPUCK_ANALOG_CYCLE);
    microphone_scans = scans_before(first, COUNT_ACCELEROMETER_FINISHED);
    if (scans_before(first, COUNT_AMBIENT_FINISHED) < microphone_scans)
        microphone_scans = scans_before(first, COUNT_AMBIENT_FINISHED);
    if (scans_before(first, COUNT_LIT_FINISHED) < microphone_scans)
        microphone_scans = scans_before(first, COUNT_LIT_FINISHED);
    run = scans < microphone_scans ? scans : microphone_scans;
    // The scans of the run that leave the next one to the microphones.
    scans = run == microphone_scans ? (uint16_t)(run - 1u) : run;
    if (scans > 0u) {
        epuck_microphones_sampled_run(
          analog->microphones, values, analog->previous == EPUCK_ANALOG_MICROPHONES, scans);
        analog->previous = EPUCK_ANALOG_MICROPHONES;
        analog->count = (uint8_t)((analog->count + scans) % EPUCK_ANALOG_CYCLE);
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
