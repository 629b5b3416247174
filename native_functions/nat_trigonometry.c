// Integer trigonometry and square root (language.md §13.3) and the natives
// built on them. The algorithms and tables reproduce upstream Aseba bit for
// bit, which programs observe, so they are data rather than a formula.
//
// Angles: int16 where 32768 is pi. Sines: 1.15 fixed point.

#include <stddef.h>

#include "nat_internal.h"
#include "nat_standard.h"

#define QUARTER_TURN       16384 // pi/2
#define HALF_TURN          32768 // pi, one more than INT16_MAX
#define SINE_ONE           32767 // sin(pi/2)
#define SINE_FRACTION_BITS 15    // sines are 1.15 fixed point

// sin over a quarter turn: SINE[i] ~ 32767 sin(pi i / 256), with
// corrections made upstream, so 128 steps of 128 angle units each.
#define SINE_STEP_BITS 7
#define SINE_STEP      (1 << SINE_STEP_BITS)
static const int16_t SINE[129] = {
    0,     403,   804,   1207,  1608,  2010,  2411,  2812,  3212,  3612,  4011,  4411,  4808,
    5206,  5603,  5998,  6393,  6787,  7180,  7572,  7962,  8352,  8740,  9127,  9513,  9896,
    10279, 10660, 11040, 11417, 11794, 12167, 12540, 12911, 13279, 13646, 14010, 14373, 14733,
    15091, 15447, 15801, 16151, 16500, 16846, 17190, 17531, 17869, 18205, 18538, 18868, 19196,
    19520, 19842, 20160, 20476, 20788, 21097, 21403, 21706, 22006, 22302, 22595, 22884, 23171,
    23453, 23732, 24008, 24279, 24548, 24812, 25073, 25330, 25583, 25833, 26078, 26320, 26557,
    26791, 27020, 27246, 27467, 27684, 27897, 28106, 28311, 28511, 28707, 28899, 29086, 29269,
    29448, 29622, 29792, 29957, 30117, 30274, 30425, 30572, 30715, 30852, 30985, 31114, 31238,
    31357, 31471, 31581, 31686, 31786, 31881, 31972, 32057, 32138, 32215, 32285, 32352, 32413,
    32470, 32521, 32569, 32610, 32647, 32679, 32706, 32728, 32746, 32758, 32766, 32767
};

// atan over octaves of the ratio y/x: ATAN[8k + m] ~ (32768/pi)
// atan(2^(k-4) (1 + m/8)), with upstream's corrections; the last is pi/2.
#define ATAN_BINS_PER_OCTAVE 8
#define ATAN_LOWEST_OCTAVE   12 // below 2^12 (ratio 1/16), atan is linear
#define ATAN_FRACTION_BITS   16 // the ratio y/x is computed in 16.16
#define ATAN_POSITION_BITS   8  // bits kept of the ratio below its top bit
#define ATAN_BIN_SHIFT       5  // the top 3 of them choose the bin
#define ATAN_BIN_WEIGHT      (1 << ATAN_BIN_SHIFT)
static const int16_t ATAN[161] = {
    652,   735,   816,   896,   977,   1058,  1139,  1218,  1300,  1459,  1620,  1777,  1935,
    2093,  2250,  2403,  2556,  2868,  3164,  3458,  3748,  4029,  4307,  4578,  4839,  5359,
    5836,  6290,  6720,  7126,  7507,  7861,  8203,  8825,  9357,  9839,  10260, 10640, 10976,
    11281, 11557, 12037, 12425, 12755, 13036, 13277, 13486, 13671, 13837, 14112, 14331, 14514,
    14666, 14796, 14907, 15003, 15091, 15235, 15348, 15441, 15519, 15585, 15642, 15691, 15736,
    15808, 15865, 15912, 15951, 15984, 16013, 16037, 16060, 16096, 16125, 16148, 16168, 16184,
    16199, 16211, 16222, 16240, 16255, 16266, 16276, 16284, 16292, 16298, 16303, 16312, 16320,
    16325, 16331, 16334, 16338, 16341, 16344, 16348, 16352, 16355, 16357, 16360, 16361, 16363,
    16364, 16366, 16369, 16369, 16371, 16372, 16373, 16373, 16375, 16375, 16377, 16376, 16378,
    16378, 16378, 16379, 16379, 16380, 16380, 16380, 16382, 16381, 16381, 16381, 16382, 16382,
    16382, 16382, 16382, 16382, 16384, 16383, 16383, 16383, 16383, 16383, 16383, 16383, 16383,
    16383, 16383, 16383, 16384, 16384, 16384, 16384, 16384, 16384, 16384, 16384, 16384, 16384,
    16384, 16384, 16384, 16384, 16384
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
        uint16_t index = folded >> SINE_STEP_BITS;
        uint16_t fraction = folded & (SINE_STEP - 1);
        uint16_t step = (uint16_t)(SINE[index + 1] - SINE[index]);
        sine = (uint16_t)(SINE[index] + (uint16_t)(step * fraction) / SINE_STEP);
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
            angle = nat_wrap(((int32_t)ATAN[0] * ratio) >> ATAN_LOWEST_OCTAVE);
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
            int16_t step = (int16_t)(ATAN[bin + 1] - ATAN[bin]);
            angle = (int16_t)(ATAN[bin] + ((int16_t)(step * weight) >> ATAN_BIN_SHIFT));
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

void nat_math_atan2_function(vm_state *vm, const int16_t *arguments)
{
    nat_elementwise_binary(vm, arguments, nat_atan2);
}

void nat_math_sin_function(vm_state *vm, const int16_t *arguments)
{
    nat_elementwise_unary(vm, arguments, nat_sin);
}

void nat_math_cos_function(vm_state *vm, const int16_t *arguments)
{
    nat_elementwise_unary(vm, arguments, nat_cos);
}

void nat_math_rot2_function(vm_state *vm, const int16_t *arguments)
{
    int16_t *vectors[2];
    if (!nat_spans(vm, arguments, 2, 2, vectors))
        return;
    const int16_t *angle = vm_variables(vm, (uint16_t)arguments[2], 1);
    if (angle == NULL)
        return;
    int16_t *dest = vectors[0];
    // Everything is read before dest is written: they may overlap.
    int32_t x = vectors[1][0];
    int32_t y = vectors[1][1];
    int32_t cosine = nat_cos(*angle);
    int32_t sine = nat_sin(*angle);
    // Each product is at most 2^30 in magnitude, so the sums fit in 32 bits.
    dest[0] = nat_wrap((cosine * x - sine * y) >> SINE_FRACTION_BITS);
    dest[1] = nat_wrap((cosine * y + sine * x) >> SINE_FRACTION_BITS);
}

void nat_math_sqrt_function(vm_state *vm, const int16_t *arguments)
{
    int16_t *spans[2];
    uint16_t length = nat_size_after(arguments, 2);
    if (!nat_spans(vm, arguments, 2, length, spans))
        return;
    for (uint16_t i = 0; i < length; ++i) {
        int16_t value = spans[1][i];
        if (value < 0) {
            vm_error_node_specific(vm, "Negative input to sqrt");
            return;
        }
        spans[0][i] = nat_sqrt(value);
    }
}
