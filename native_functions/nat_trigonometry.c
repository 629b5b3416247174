// Integer trigonometry and square root (language.md §13.3), which the
// math.* natives (nat_math.c) apply element by element. The algorithms and tables reproduce
// upstream Aseba bit for bit, which programs observe, so they are data rather than a formula.
//
// Angles: int16 where 32768 is pi. Sines: 1.15 fixed point.

#include <stddef.h>

#include "nat_internal.h"
#include "nat_standard.h"

#define QUARTER_TURN 16384 // pi/2
#define HALF_TURN    32768 // pi, one more than INT16_MAX
#define SINE_ONE     32767 // sin(pi/2)

// sin over a quarter turn, 129 entries: SINE[i] ~ 32767 sin(pi i / 256),
// with upstream's corrections, so 128 steps of 128 angle units each. The
// table is kept as its second differences, 80 bytes instead of 258: in each
// segment of 32 entries, entry 32s is SINE_START[s] and rises by
// SINE_RISE[s] to the next; each rise differs from the one before by a
// nibble of SINE_BENDS less 8 (entry k's in the low nibble of byte k / 2
// when k is even). tests/native_functions compares every angle with upstream.
#define SINE_STEP_BITS    7
#define SINE_STEP         (1 << SINE_STEP_BITS)
#define SINE_SEGMENT_BITS 5
#define NIBBLE_BITS       4
#define NIBBLE_MASK       0xF
#define NIBBLE_BIAS       8
#define SINE_SEGMENTS     4 // of 32 entries: 128 steps
static const uint16_t SINE_START[SINE_SEGMENTS] = { 0, 12540, 23171, 30274 };
static const uint16_t SINE_RISE[SINE_SEGMENTS] = { 403, 371, 282, 151 };
static const uint8_t SINE_BENDS[64] = {
    0xA6, 0x96, 0x87, 0x87, 0x97, 0x95, 0x67, 0x78, 0x77, 0x86, 0x76, 0x57, 0x68, 0x57, 0x48, 0x68,
    0x75, 0x75, 0x65, 0x66, 0x74, 0x65, 0x55, 0x56, 0x65, 0x64, 0x64, 0x54, 0x55, 0x45, 0x45, 0x36,
    0x55, 0x63, 0x53, 0x44, 0x35, 0x35, 0x35, 0x35, 0x44, 0x44, 0x43, 0x34, 0x44, 0x43, 0x33, 0x25,
    0x44, 0x42, 0x34, 0x33, 0x34, 0x33, 0x24, 0x44, 0x51, 0x42, 0x52, 0x41, 0x33, 0x43, 0x42, 0x81,
};

// SINE[index] for index < 128, and its rise to SINE[index + 1] in `rise`:
// at most 31 steps from the segment's start.
static uint16_t sine_entry(uint16_t index, uint16_t *rise)
{
    uint16_t segment = index >> SINE_SEGMENT_BITS;
    uint16_t value = SINE_START[segment];
    uint16_t step = SINE_RISE[segment];
    uint16_t k;

    for (k = (uint16_t)(segment << SINE_SEGMENT_BITS); k < index; k++) {
        uint8_t bends = SINE_BENDS[k >> 1];
        if (k & 1)
            bends >>= NIBBLE_BITS;
        value = (uint16_t)(value + step);
        step = (uint16_t)(step + (bends & NIBBLE_MASK) - NIBBLE_BIAS);
    }
    *rise = step;
    return value;
}

// atan over octaves of the ratio y/x: ATAN[8k + m] ~ (32768/pi)
// atan(2^(k-4) (1 + m/8)), with upstream's corrections; the last is pi/2.
#define ATAN_BINS_PER_OCTAVE 8
#define ATAN_LOWEST_OCTAVE   12 // below 2^12 (ratio 1/16), atan is linear
#define ATAN_FRACTION_BITS   16 // the ratio y/x is computed in 16.16
#define ATAN_POSITION_BITS   8  // bits kept of the ratio below its top bit
#define ATAN_BIN_SHIFT       5  // the top 3 of them choose the bin
#define ATAN_BIN_WEIGHT      (1 << ATAN_BIN_SHIFT)
// The table is kept in two parts, 238 bytes instead of 322: its first
// ATAN_HEAD_ENTRIES entries, and from the last of them on (ratios above 40),
// where every entry lies within 255 of pi/2, each entry's distance below
// pi/2 in a byte.
#define ATAN_ENTRIES      161
#define ATAN_HEAD_ENTRIES 76
static const int16_t ATAN_HEAD[ATAN_HEAD_ENTRIES] = {
    652,   735,   816,   896,   977,   1058,  1139,  1218,  1300,  1459,  1620,  1777,  1935,
    2093,  2250,  2403,  2556,  2868,  3164,  3458,  3748,  4029,  4307,  4578,  4839,  5359,
    5836,  6290,  6720,  7126,  7507,  7861,  8203,  8825,  9357,  9839,  10260, 10640, 10976,
    11281, 11557, 12037, 12425, 12755, 13036, 13277, 13486, 13671, 13837, 14112, 14331, 14514,
    14666, 14796, 14907, 15003, 15091, 15235, 15348, 15441, 15519, 15585, 15642, 15691, 15736,
    15808, 15865, 15912, 15951, 15984, 16013, 16037, 16060, 16096, 16125, 16148,
};
#define ATAN_TAIL_FIRST (ATAN_HEAD_ENTRIES - 1)
static const uint8_t ATAN_TAIL[ATAN_ENTRIES - ATAN_TAIL_FIRST] = {
    236, 216, 200, 185, 173, 162, 144, 129, 118, 108, 100, 92, 86, 81, 72, 64, 59, 53,
    50,  46,  43,  40,  36,  32,  29,  27,  24,  23,  21,  20, 18, 15, 15, 13, 12, 11,
    11,  9,   9,   7,   8,   6,   6,   6,   5,   5,   4,   4,  4,  2,  3,  3,  3,  2,
    2,   2,   2,   2,   2,   0,   1,   1,   1,   1,   1,   1,  1,  1,  1,  1,  1,  0,
    0,   0,   0,   0,   0,   0,   0,   0,   0,   0,   0,   0,  0,  0,
};

int16_t nat_sin(int16_t angle)
{
    // Fold |angle| (32768 for -pi) onto the first quarter turn.
    bool negative = angle < 0;
    uint16_t folded = (uint16_t)(negative ? -(int32_t)angle : angle);
    if (folded > QUARTER_TURN)
        folded = (uint16_t)(HALF_TURN - folded);

    uint16_t sine;
    if (folded == QUARTER_TURN) {
        sine = SINE_ONE; // the last entry: there is none after it to interpolate
    } else {
        // Interpolate linearly between two entries: SINE[i] (128 - f) / 128 +
        // SINE[i + 1] f / 128, rounded down, is SINE[i] + step f / 128; the
        // table rises by at most 403 a step, so step * f fits 16 bits.
        uint16_t fraction = folded & (SINE_STEP - 1);
        uint16_t step;
        uint16_t entry = sine_entry(folded >> SINE_STEP_BITS, &step);
        sine = (uint16_t)(entry + (uint16_t)(step * fraction) / SINE_STEP);
    }
    return (int16_t)(negative ? -(int16_t)sine : (int16_t)sine);
}

int16_t nat_cos(int16_t angle)
{
    return nat_sin(nat_wrap((int32_t)angle + QUARTER_TURN));
}

int16_t nat_atan2(int16_t y, int16_t x)
{
    if (y == 0)
        return x >= 0 ? 0 : INT16_MIN;

    // As upstream, |-32768| stays -32768 and the ratio below is negative.
    int16_t x_magnitude = nat_wrap(x < 0 ? -(int32_t)x : x);
    int16_t y_magnitude = nat_wrap(y < 0 ? -(int32_t)y : y);
    int16_t angle;
    if (x == 0) {
        angle = QUARTER_TURN;
    } else {
        // |y| * 65536 is at most 2^31 in magnitude, and |x| is never -1.
        int32_t ratio = ((int32_t)y_magnitude * ((int32_t)1 << ATAN_FRACTION_BITS)) / x_magnitude;
        if (ratio >= 0 && ratio < ((int32_t)1 << ATAN_LOWEST_OCTAVE)) {
            angle = nat_wrap(((int32_t)ATAN_HEAD[0] * ratio) >> ATAN_LOWEST_OCTAVE);
        } else {
            // Keep the top bit of the ratio and the ATAN_POSITION_BITS below
            // it, moving one octave (8 bins) on for each bit dropped; modulo
            // 2^32, as upstream, so the top bit of a negative ratio is its sign.
            uint32_t top = (uint32_t)ratio >> (ATAN_LOWEST_OCTAVE - ATAN_POSITION_BITS);
            uint16_t bin = 0;
            while (top >> (ATAN_POSITION_BITS + 1) != 0) {
                top >>= 1;
                bin += ATAN_BINS_PER_OCTAVE;
            }
            int16_t position = (int16_t)(top - ((uint32_t)1 << ATAN_POSITION_BITS));
            bin += (uint16_t)(position >> ATAN_BIN_SHIFT);
            // Interpolate as sin does: (ATAN[b] (32 - w) + ATAN[b + 1] w) / 32
            // rounded down is ATAN[b] + step w / 32 rounded down (an
            // arithmetic shift), and |step| <= 520 keeps step * w in 16 bits.
            int16_t weight = position & (ATAN_BIN_WEIGHT - 1);
            int16_t entry, step;
            if (bin < ATAN_TAIL_FIRST) {
                entry = ATAN_HEAD[bin];
                step = (int16_t)(ATAN_HEAD[bin + 1] - entry);
            } else {
                const uint8_t *below = &ATAN_TAIL[bin - ATAN_TAIL_FIRST];
                entry = (int16_t)(QUARTER_TURN - below[0]);
                step = (int16_t)(below[0] - below[1]);
            }
            angle = (int16_t)(entry + ((int16_t)(step * weight) >> ATAN_BIN_SHIFT));
        }
        if (x < 0)
            angle = nat_wrap(HALF_TURN - (int32_t)angle);
    }
    return y > 0 ? angle : nat_wrap(-(int32_t)angle);
}

int16_t nat_sqrt(int16_t x)
{
    if (x < 0)
        return 0;
    // Digit by digit in base 4, from the highest power of 4 below 2^15.
    uint16_t remainder = (uint16_t)x;
    uint16_t root = 0;
    uint16_t bit = (uint16_t)1 << 14;
    while (bit > remainder)
        bit >>= 2;
    while (bit != 0) {
        if (remainder >= root + bit) {
            remainder -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return (int16_t)root;
}
