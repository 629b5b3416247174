// The 12-bit ADC (§2.3): single conversions started by hand, and scans of a
// few channels converted back to back by the ADC's own sequencer, with an
// interrupt after each scan at EPUCK_ADC_SCAN_RATE_HZ (as the library's
// advanced driver, used by the upstream Aseba firmware).

#include "epuck_dspic30_board.h"
#include "ports/dspic30/dspic30_registers.h"

#define MICROSECONDS_PER_SECOND 1000000ul
#define CYCLES_PER_SCAN         (DSPIC30_FCY_HZ / EPUCK_ADC_SCAN_RATE_HZ)
#define TAD_PER_CHANNEL         (DSPIC30_ADC_SAMPLE_TAD + DSPIC30_ADC_CONVERSION_TAD)
// Tad = Tcy × (ADCS + 1) / 2: twice the cycles give whole numbers.
#define HALF_CYCLES_PER_TAD_STEP 2u

typedef char
  scan_rate_is_a_whole_number_of_cycles[DSPIC30_FCY_HZ % EPUCK_ADC_SCAN_RATE_HZ == 0 ? 1 : -1];

static uint8_t count_channels(uint16_t mask)
{
    uint8_t count = 0;
    for (; mask != 0; mask = (uint16_t)(mask >> 1))
        count = (uint8_t)(count + (mask & 1u));
    return count;
}

// ADCS + 1 for a scan of n channels (index n), or 0 where n channels cannot
// fill the scan period with whole Tad. Constants: the ADC's interrupt sets
// the next scan after each one (epuck_board_adc_scan_select), and with the
// 32-bit divisions done there it took longer than the 61 µs between two
// scans, so that UART1 below it overran (docs/dspic30-sim.md).
#define HALF_CYCLES_PER_SCAN (HALF_CYCLES_PER_TAD_STEP * CYCLES_PER_SCAN)
#define TAD_STEPS(n)                                                                               \
    (HALF_CYCLES_PER_SCAN % ((n)*TAD_PER_CHANNEL) == 0                                             \
       ? HALF_CYCLES_PER_SCAN / ((n)*TAD_PER_CHANNEL)                                              \
       : 0u)
static const uint16_t tad_steps[] = {
    0u, TAD_STEPS(1u), TAD_STEPS(2u), TAD_STEPS(3u), TAD_STEPS(4u), TAD_STEPS(5u), TAD_STEPS(6u)
};
typedef char table_covers_every_scan
  [sizeof tad_steps / sizeof tad_steps[0] == EPUCK_ADC_SCAN_MAX_CHANNELS + 1u ? 1 : -1];

bool dspic30_adc_scan_clock(uint8_t channel_count, uint16_t *adcs)
{
    uint16_t steps;

    if (channel_count == 0 || channel_count > EPUCK_ADC_SCAN_MAX_CHANNELS)
        return false;
    steps = tad_steps[channel_count]; // ADCS + 1
    if (steps < DSPIC30_ADC_MIN_ADCS + 1u || steps > DSPIC30_ADC_MAX_ADCS + 1u)
        return false;
    *adcs = (uint16_t)(steps - 1u);
    return true;
}

void dspic30_adc_init(hal_board *board)
{
    board->adc_scan_callback = 0;
    board->adc_scan_context = 0;
    board->adc_scan_mask = 0;
    board->adc_scan_count = 0;

    // Manual sampling and conversion (SSRC = 000), unsigned integers,
    // AVdd/AVss reference, one result in ADCBUF0.
    dspic30_write(DSPIC30_ADCON1, 0);
    dspic30_write(DSPIC30_ADCON2, 0);
    dspic30_write(DSPIC30_ADCON3, DSPIC30_ADC_SINGLE_ADCS);
    dspic30_write(DSPIC30_ADCHS, 0);
    dspic30_write(DSPIC30_ADPCFG, DSPIC30_ADC_DIGITAL_INPUTS);
    dspic30_write(DSPIC30_ADCSSL, 0);
    dspic30_set_priority(DSPIC30_IPC_ADC, DSPIC30_SHIFT_ADC, DSPIC30_PRIORITY_ADC);
    dspic30_clear_bits(DSPIC30_IEC0, DSPIC30_IRQ0_ADC);
    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_ADC);
    dspic30_write(DSPIC30_ADCON1, DSPIC30_ADCON1_ADON);
}

uint16_t epuck_board_adc_read(hal_board *board, uint8_t channel)
{
    uint16_t attempts;

    if (channel >= EPUCK_ADC_CHANNEL_COUNT || board->adc_scan_mask != 0)
        return 0;
    dspic30_write(DSPIC30_ADCHS, channel);
    dspic30_set_bits(DSPIC30_ADCON1, DSPIC30_ADCON1_SAMP);
    hal_delay_microseconds(board, DSPIC30_ADC_SAMPLE_WAIT_US);
    // Ending the sampling starts the conversion.
    dspic30_clear_bits(DSPIC30_ADCON1, DSPIC30_ADCON1_SAMP);
    for (attempts = 0; attempts < DSPIC30_ADC_CONVERSION_ATTEMPTS; attempts++) {
        if (dspic30_read(DSPIC30_ADCON1) & DSPIC30_ADCON1_DONE)
            return dspic30_read(DSPIC30_ADCBUF0);
    }
    return 0;
}

// Programs the sequencer for `mask` (already validated) and starts it.
static void configure_scan(hal_board *board, uint16_t mask, uint8_t count, uint16_t adcs)
{
    dspic30_write(DSPIC30_ADCON1, 0); // stop: the running scan is dropped
    board->adc_scan_mask = mask;
    board->adc_scan_count = count;
    dspic30_write(DSPIC30_ADCHS, 0);
    dspic30_write(DSPIC30_ADCSSL, mask);
    dspic30_write(DSPIC30_ADCON3,
                  (uint16_t)((DSPIC30_ADC_SAMPLE_TAD << DSPIC30_ADCON3_SAMC_SHIFT) | adcs));
    // Scan the inputs of ADCSSL; interrupt after `count` conversions.
    dspic30_write(
      DSPIC30_ADCON2,
      (uint16_t)(DSPIC30_ADCON2_CSCNA | ((uint16_t)(count - 1u) << DSPIC30_ADCON2_SMPI_SHIFT)));
    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_ADC);
    dspic30_set_bits(DSPIC30_IEC0, DSPIC30_IRQ0_ADC);
    // Automatic sampling, and the internal counter ends each sample.
    dspic30_write(DSPIC30_ADCON1, DSPIC30_ADCON1_SSRC_AUTO | DSPIC30_ADCON1_ASAM);
    dspic30_set_bits(DSPIC30_ADCON1, DSPIC30_ADCON1_ADON);
}

static bool scan_parameters(uint16_t mask, uint8_t *count, uint16_t *adcs)
{
    *count = count_channels(mask);
    return *count >= EPUCK_ADC_SCAN_MIN_CHANNELS && *count <= EPUCK_ADC_SCAN_MAX_CHANNELS &&
           dspic30_adc_scan_clock(*count, adcs);
}

bool epuck_board_adc_scan_start(hal_board *board,
                                uint16_t channel_mask,
                                epuck_adc_scan_callback callback,
                                void *context)
{
    uint8_t count;
    uint16_t adcs;
    hal_critical_state state;

    if (!scan_parameters(channel_mask, &count, &adcs))
        return false;
    state = hal_critical_enter(board);
    board->adc_scan_callback = callback;
    board->adc_scan_context = context;
    configure_scan(board, channel_mask, count, adcs);
    hal_critical_leave(board, state);
    return true;
}

bool epuck_board_adc_scan_select(hal_board *board, uint16_t channel_mask)
{
    uint8_t count;
    uint16_t adcs;
    hal_critical_state state;

    if (board->adc_scan_mask == 0 || !scan_parameters(channel_mask, &count, &adcs))
        return false;
    state = hal_critical_enter(board);
    configure_scan(board, channel_mask, count, adcs);
    hal_critical_leave(board, state);
    return true;
}

void epuck_board_adc_scan_stop(hal_board *board)
{
    hal_critical_state state = hal_critical_enter(board);
    dspic30_write(DSPIC30_ADCON1, 0);
    dspic30_clear_bits(DSPIC30_IEC0, DSPIC30_IRQ0_ADC);
    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_ADC);
    board->adc_scan_mask = 0;
    board->adc_scan_callback = 0;
    dspic30_adc_init(board); // back to single conversions
    hal_critical_leave(board, state);
}

void epuck_board_adc_scan_runs(hal_board *board, epuck_adc_scan_run_callback callback)
{
    // The chip interrupts once per scan: every scan goes to the scan callback.
    (void)board;
    (void)callback;
}

void dspic30_on_adc(hal_board *board)
{
    uint16_t values[EPUCK_ADC_SCAN_MAX_CHANNELS];
    uint8_t count = board->adc_scan_count;
    uint8_t i;

    dspic30_clear_bits(DSPIC30_IFS0, DSPIC30_IRQ0_ADC);
    if (board->adc_scan_mask == 0 || count > EPUCK_ADC_SCAN_MAX_CHANNELS)
        return;
    // The sequencer fills ADCBUF0.. in ascending channel order.
    for (i = 0; i < count; i++)
        values[i] = dspic30_read((uint16_t)(DSPIC30_ADCBUF0 + 2u * i));
    if (board->adc_scan_callback)
        board->adc_scan_callback(board->adc_scan_context, values, count);
}
