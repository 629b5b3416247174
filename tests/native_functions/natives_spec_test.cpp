// The standard math natives against expectations computed here, independently
// of our implementation: double-precision trigonometry, int32 arithmetic
// truncated to 16 bits, the LCG formula, and the error rules of
// language.md §13.2 / bytecode.md §8.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "our_node.hpp"

namespace
{

using Words = std::vector<int16_t>;

constexpr uint16_t memory_words = 512;

// Values at the edges of int16 arithmetic.
const Words boundary_values = { -32768, -32767, -2, -1, 0, 1, 2, 32766, 32767 };

// Two arrays holding every ordered pair of boundary values.
void boundary_pairs(Words &left, Words &right)
{
    for (int16_t a : boundary_values)
        for (int16_t b : boundary_values) {
            left.push_back(a);
            right.push_back(b);
        }
}

int16_t truncate(int64_t value)
{
    return static_cast<int16_t>(value); // C++20: modulo 2^16
}

// Runs a dest/src1/src2 native over all boundary pairs and checks every
// element against `expected` computed in 64 bits then truncated.
template<typename Expected>
void check_binary(const vm_native &native, Expected expected, bool skip_zero_divisor = false)
{
    Words left, right;
    boundary_pairs(left, right);
    if (skip_zero_divisor) {
        Words kept_left, kept_right;
        for (size_t i = 0; i < left.size(); ++i)
            if (right[i] != 0) {
                kept_left.push_back(left[i]);
                kept_right.push_back(right[i]);
            }
        left = kept_left;
        right = kept_right;
    }
    OurNode node(memory_words);
    const int16_t size = static_cast<int16_t>(left.size());
    node.put(100, left);
    node.put(200, right);
    node.call(native, { 0, 100, 200, size });
    const std::string name = description_of(native).name;
    ASSERT_FALSE(node.stopped()) << name;
    for (size_t i = 0; i < left.size(); ++i)
        EXPECT_EQ(node.variables[i], truncate(expected(left[i], right[i])))
          << name << "(" << left[i] << ", " << right[i] << ")";
    EXPECT_EQ(node.get(100, size), left);
    EXPECT_EQ(node.get(200, size), right);
}

// --- trigonometry and square root -------------------------------------------

// sin/cos interpolate linearly a table of about 32767 sin(pi i / 256) (its
// entries within 2 units, language.md §13.3) and truncate: the interpolation
// adds at most (pi/256)^2 / 8 * 32767 = 0.62 units, the truncation under 1.
constexpr double trig_tolerance = 4.0;

double angle_radians(int angle)
{
    return std::numbers::pi * angle / 32768.0;
}

TEST(NativeTrigonometry, SineWithinToleranceOfDoubleForEveryAngle)
{
    for (int angle = -32768; angle <= 32767; ++angle)
        ASSERT_NEAR(nat_sin(static_cast<int16_t>(angle)),
                    32767 * std::sin(angle_radians(angle)),
                    trig_tolerance)
          << "angle " << angle;
}

TEST(NativeTrigonometry, CosineWithinToleranceOfDoubleForEveryAngle)
{
    for (int angle = -32768; angle <= 32767; ++angle)
        ASSERT_NEAR(nat_cos(static_cast<int16_t>(angle)),
                    32767 * std::cos(angle_radians(angle)),
                    trig_tolerance)
          << "angle " << angle;
}

TEST(NativeTrigonometry, SineExtremesAreExact)
{
    EXPECT_EQ(nat_sin(16384), 32767);
    EXPECT_EQ(nat_sin(-16384), -32767);
    EXPECT_EQ(nat_sin(0), 0);
    EXPECT_EQ(nat_cos(0), 32767);
}

TEST(NativeTrigonometry, SqrtIsTheExactFloorForEveryNonNegativeInput)
{
    for (int32_t x = 0; x <= 32767; ++x) {
        int32_t root = nat_sqrt(static_cast<int16_t>(x));
        ASSERT_LE(root * root, x) << x;
        ASSERT_GT((root + 1) * (root + 1), x) << x;
    }
}

// The table interpolation of atan2 is coarser: within 0.2 degree (36 units),
// away from -32768, whose magnitude upstream keeps negative.
constexpr double atan2_tolerance = 36.0;

TEST(NativeTrigonometry, Atan2WithinToleranceOfDoubleOverAGrid)
{
    std::vector<int> values;
    for (int v = -32767; v <= 32767; v += 113)
        values.push_back(v);
    for (int v : { -1000, -100, -10, -2, -1, 1, 2, 10, 100, 1000, 32767, -32767 })
        values.push_back(v);
    for (int y : values)
        for (int x : values) {
            double expected = 32768 / std::numbers::pi * std::atan2(y, x);
            double error =
              std::abs(nat_atan2(static_cast<int16_t>(y), static_cast<int16_t>(x)) - expected);
            error = std::min(error, std::abs(error - 65536)); // -pi and pi are one angle
            ASSERT_LE(error, atan2_tolerance) << "atan2(" << y << ", " << x << ")";
        }
}

TEST(NativeTrigonometry, Atan2SpecialCasesOfTheSpecification)
{
    EXPECT_EQ(nat_atan2(0, 5), 0);
    EXPECT_EQ(nat_atan2(0, 0), 0);
    EXPECT_EQ(nat_atan2(0, -5), -32768);
    EXPECT_EQ(nat_atan2(7, 0), 16384);
    EXPECT_EQ(nat_atan2(-7, 0), -16384);
    // language.md §13.3: the 32-bit wrap of upstream when one input is -32768.
    EXPECT_EQ(nat_atan2(32767, -32768), 16384);
    EXPECT_EQ(nat_atan2(-32768, 32767), -16384);
}

TEST(NativeTrigonometry, VectorNativesApplyTheFunctionsElementwise)
{
    OurNode node(memory_words);
    Words angles = { -32768, -16384, -1, 0, 1, 8192, 16384, 32767 };
    const auto size = static_cast<int16_t>(angles.size());
    node.put(100, angles);
    node.call(standard_native("math.sin"), { 0, 100, size });
    node.call(standard_native("math.cos"), { 20, 100, size });
    node.put(200, { 0, 1, 2, 3, 4, 99, 100, 32767 });
    node.call(standard_native("math.sqrt"), { 40, 200, size });
    ASSERT_FALSE(node.stopped());
    for (size_t i = 0; i < angles.size(); ++i) {
        EXPECT_NEAR(node.variables[i], 32767 * std::sin(angle_radians(angles[i])), trig_tolerance);
        EXPECT_NEAR(
          node.variables[20 + i], 32767 * std::cos(angle_radians(angles[i])), trig_tolerance);
    }
    EXPECT_EQ(node.get(40, size), (Words{ 0, 1, 1, 1, 2, 9, 10, 181 }));

    node.put(300, { 1, -1, 0, 0 });
    node.put(310, { 0, 0, 1, -1 });
    node.call(standard_native("math.atan2"), { 60, 300, 310, 4 });
    EXPECT_EQ(node.get(60, 4), (Words{ 16384, -16384, 0, -32768 }));
}

TEST(NativeTrigonometry, SqrtOfANegativeStopsAfterTheEarlierElements)
{
    OurNode node(memory_words);
    node.put(0, { 77, 77, 77, 77 });
    node.put(100, { 4, 9, -1, 16 });
    node.call(standard_native("math.sqrt"), { 0, 100, 4 });
    EXPECT_TRUE(node.stopped());
    EXPECT_EQ(node.get(0, 4), (Words{ 2, 3, 77, 77 }));
    ASSERT_EQ(node.errors.size(), 1u);
    EXPECT_EQ(
      node.errors[0],
      (ErrorReport{
        ErrorReport::Kind::node_specific, OurNode::call_pc, 0, 0, "Negative input to sqrt" }));
}

TEST(NativeTrigonometry, Rot2RotatesLikeDoublePrecision)
{
    std::mt19937 random(17);
    std::uniform_int_distribution<int> component(-10000, 10000);
    std::uniform_int_distribution<int> angle(-32768, 32767);
    for (int trial = 0; trial < 2000; ++trial) {
        OurNode node(16);
        const int x = component(random), y = component(random), a = angle(random);
        node.put(2, { static_cast<int16_t>(x), static_cast<int16_t>(y) });
        node.put(4, { static_cast<int16_t>(a) });
        node.call(standard_native("math.rot2"), { 0, 2, 4 });
        const double c = std::cos(angle_radians(a)), s = std::sin(angle_radians(a));
        // Sines within 4/32767 give 2 x 10000 x 4/32767 < 2.5 units, the
        // scale 32767/32768 under 0.5 more, the floor under 1.
        EXPECT_NEAR(node.variables[0], c * x - s * y, 4.0) << x << " " << y << " " << a;
        EXPECT_NEAR(node.variables[1], c * y + s * x, 4.0) << x << " " << y << " " << a;
    }
}

TEST(NativeTrigonometry, Rot2ReadsItsInputsBeforeWriting)
{
    // dest overlaps v: the result must be that of the unaliased call.
    OurNode plain(16), aliased(16);
    plain.put(2, { 1000, 2000 });
    plain.put(4, { 4096 });
    plain.call(standard_native("math.rot2"), { 0, 2, 4 });
    aliased.put(2, { 1000, 2000 });
    aliased.put(4, { 4096 });
    aliased.call(standard_native("math.rot2"), { 2, 2, 4 });
    EXPECT_EQ(aliased.get(2, 2), plain.get(0, 2));
}

// --- element-wise arithmetic ------------------------------------------------

TEST(NativeMath, AddSubMulWrapLikeInt32Truncated)
{
    check_binary(standard_native("math.add"), [](int64_t a, int64_t b) { return a + b; });
    check_binary(standard_native("math.sub"), [](int64_t a, int64_t b) { return a - b; });
    check_binary(standard_native("math.mul"), [](int64_t a, int64_t b) { return a * b; });
}

TEST(NativeMath, MinMaxAreSigned)
{
    check_binary(standard_native("math.min"), [](int64_t a, int64_t b) { return std::min(a, b); });
    check_binary(standard_native("math.max"), [](int64_t a, int64_t b) { return std::max(a, b); });
}

TEST(NativeMath, DivTruncatesTowardZeroAndWraps)
{
    check_binary(
      standard_native("math.div"), [](int64_t a, int64_t b) { return a / b; }, true);
    OurNode node(memory_words);
    node.put(100, { -7, 7, -32768 });
    node.put(200, { 2, -2, -1 });
    node.call(standard_native("math.div"), { 0, 100, 200, 3 });
    EXPECT_EQ(node.get(0, 3), (Words{ -3, -3, -32768 }));
}

TEST(NativeMath, DivByZeroStopsAfterTheEarlierElements)
{
    OurNode node(memory_words);
    node.put(0, { -5, -5, -5, -5 });
    node.put(100, { 10, 20, 30, 40 });
    node.put(200, { 1, 2, 0, 4 });
    node.call(standard_native("math.div"), { 0, 100, 200, 4 });
    EXPECT_TRUE(node.stopped());
    EXPECT_EQ(node.get(0, 4), (Words{ 10, 10, -5, -5 }));
    ASSERT_EQ(node.errors.size(), 1u);
    EXPECT_EQ(node.errors[0],
              (ErrorReport{ ErrorReport::Kind::division_by_zero, OurNode::call_pc, 0, 0, {} }));
}

TEST(NativeMath, MuldivUsesA32BitProduct)
{
    Words a, b;
    boundary_pairs(a, b);
    Words c;
    for (size_t i = 0; i < a.size(); ++i)
        c.push_back(boundary_values[(i * 5 + 1) % boundary_values.size()]);
    for (int16_t &divisor : c)
        if (divisor == 0)
            divisor = 3;
    OurNode node(memory_words);
    const auto size = static_cast<int16_t>(a.size());
    node.put(100, a);
    node.put(200, b);
    node.put(300, c);
    node.call(standard_native("math.muldiv"), { 0, 100, 200, 300, size });
    ASSERT_FALSE(node.stopped());
    for (size_t i = 0; i < a.size(); ++i)
        EXPECT_EQ(node.variables[i], truncate(int64_t{ a[i] } * b[i] / c[i]))
          << a[i] << " * " << b[i] << " / " << c[i];

    node.put(300, { 1, 0 });
    node.put(0, { 9, 9 });
    node.call(standard_native("math.muldiv"), { 0, 100, 200, 300, 2 });
    EXPECT_TRUE(node.stopped());
    EXPECT_EQ(node.get(0, 2), (Words{ truncate(int64_t{ a[0] } * b[0]), 9 }));
    EXPECT_EQ(node.errors.back().kind, ErrorReport::Kind::division_by_zero);
}

TEST(NativeMath, ClampBoundsEachElement)
{
    Words src, low;
    boundary_pairs(src, low);
    Words high;
    for (size_t i = 0; i < src.size(); ++i)
        high.push_back(boundary_values[(i * 7 + 3) % boundary_values.size()]);
    OurNode node(memory_words);
    const auto size = static_cast<int16_t>(src.size());
    node.put(100, src);
    node.put(200, low);
    node.put(300, high);
    node.call(standard_native("math.clamp"), { 0, 100, 200, 300, size });
    for (size_t i = 0; i < src.size(); ++i) {
        int16_t expected = src[i] > high[i] ? high[i] : src[i] < low[i] ? low[i] : src[i];
        EXPECT_EQ(node.variables[i], expected) << src[i] << " " << low[i] << " " << high[i];
    }
}

TEST(NativeMath, CopyFillAddscalar)
{
    OurNode node(memory_words);
    node.put(100, { 1, -2, 32767, -32768 });
    node.call(standard_native("math.copy"), { 0, 100, 4 });
    EXPECT_EQ(node.get(0, 4), (Words{ 1, -2, 32767, -32768 }));

    node.put(10, { -9 });
    node.call(standard_native("math.fill"), { 20, 10, 3 });
    EXPECT_EQ(node.get(20, 3), (Words{ -9, -9, -9 }));

    node.put(30, { 1 });
    node.call(standard_native("math.addscalar"), { 40, 100, 30, 4 });
    EXPECT_EQ(node.get(40, 4), (Words{ 2, -1, -32768, -32767 }));
}

TEST(NativeMath, OverlappingArgumentsActLikeAForwardLoop)
{
    // copy(a[1:4], a[0:3]) propagates a[0].
    OurNode node(memory_words);
    node.put(0, { 5, 6, 7, 8, 9 });
    node.call(standard_native("math.copy"), { 1, 0, 4 });
    EXPECT_EQ(node.get(0, 5), (Words{ 5, 5, 5, 5, 5 }));

    // addscalar reads the scalar once, even when dest overwrites it.
    node.put(0, { 1, 2, 3, 4 });
    node.call(standard_native("math.addscalar"), { 0, 0, 1, 4 });
    EXPECT_EQ(node.get(0, 4), (Words{ 3, 4, 5, 6 }));

    // add(a[1:], a, a): dest[i] = 2 src[i] with src[i] just written.
    node.put(0, { 1, 0, 0, 0 });
    node.call(standard_native("math.add"), { 1, 0, 0, 3 });
    EXPECT_EQ(node.get(0, 4), (Words{ 1, 2, 4, 8 }));
}

TEST(NativeMath, DotShiftsA32BitSum)
{
    std::mt19937 random(3);
    std::uniform_int_distribution<int> value(-32768, 32767);
    for (int trial = 0; trial < 300; ++trial) {
        const int size = 1 + trial % 8;
        Words a, b;
        for (int i = 0; i < size; ++i) {
            a.push_back(static_cast<int16_t>(value(random)));
            b.push_back(static_cast<int16_t>(value(random)));
        }
        int64_t exact = 0;
        for (int i = 0; i < size; ++i)
            exact += int64_t{ a[i] } * b[i];
        const auto sum = static_cast<int32_t>(exact); // 32-bit wrap, C++20
        for (int shift : { -20, -1, 0, 1, 5, 15, 16, 31, 32, 33, 100 }) {
            OurNode node(memory_words);
            node.put(100, a);
            node.put(200, b);
            node.put(300, { static_cast<int16_t>(shift) });
            node.call(standard_native("math.dot"),
                      { 0, 100, 200, 300, static_cast<int16_t>(size) });
            int64_t expected;
            if (shift > 32)
                expected = 0;
            else if (shift < 0) // ours: no shift (bytecode.md §11)
                expected = sum;
            else // 32: the sign of the sum
                expected = static_cast<int64_t>(sum) >> shift;
            EXPECT_EQ(node.variables[0], truncate(expected)) << "shift " << shift;
        }
    }
}

TEST(NativeMath, StatGivesMinMaxAndTruncatedMean)
{
    OurNode node(memory_words);
    node.put(100, { 3, -1, 7, 2 });
    node.call(standard_native("math.stat"), { 100, 0, 1, 2, 4 });
    EXPECT_EQ(node.get(0, 3), (Words{ -1, 7, 2 }));

    node.put(100, { -3, -4 });
    node.call(standard_native("math.stat"), { 100, 0, 1, 2, 2 });
    EXPECT_EQ(node.get(0, 3), (Words{ -4, -3, -3 }));

    node.put(100, { 32767, 32767, 32767 });
    node.call(standard_native("math.stat"), { 100, 0, 1, 2, 3 });
    EXPECT_EQ(node.get(0, 3), (Words{ 32767, 32767, 32767 }));

    // Empty: nothing written.
    node.put(0, { 11, 12, 13 });
    node.call(standard_native("math.stat"), { 100, 0, 1, 2, 0 });
    EXPECT_EQ(node.get(0, 3), (Words{ 11, 12, 13 }));

    // math.stat(v, m, m, m) leaves the mean in m.
    node.put(100, { 4, 8 });
    node.call(standard_native("math.stat"), { 100, 0, 0, 0, 2 });
    EXPECT_EQ(node.variables[0], 6);
}

TEST(NativeMath, ArgboundsKeepsFirstOccurrencesAndOnlyWritesUpdates)
{
    OurNode node(memory_words);
    node.put(100, { 5, 1, 9, 1, 9 });
    node.call(standard_native("math.argbounds"), { 100, 0, 1, 5 });
    EXPECT_EQ(node.get(0, 2), (Words{ 1, 2 }));

    node.put(0, { -7, -7 });
    node.put(100, { 32767, 32767 });
    node.call(standard_native("math.argbounds"), { 100, 0, 1, 2 });
    EXPECT_EQ(node.get(0, 2), (Words{ -7, 0 }));

    node.put(0, { -7, -7 });
    node.put(100, { -32768, -32768 });
    node.call(standard_native("math.argbounds"), { 100, 0, 1, 2 });
    EXPECT_EQ(node.get(0, 2), (Words{ 0, -7 }));

    node.call(standard_native("math.argbounds"), { 100, 0, 1, 0 });
    EXPECT_EQ(node.get(0, 2), (Words{ 0, -7 }));
}

TEST(NativeMath, SortMatchesStdSort)
{
    std::mt19937 random(5);
    std::uniform_int_distribution<int> value(-32768, 32767);
    std::uniform_int_distribution<int> small(-3, 3);
    for (int size = 0; size <= 60; ++size)
        for (int trial = 0; trial < 10; ++trial) {
            Words array;
            for (int i = 0; i < size; ++i)
                array.push_back(static_cast<int16_t>(trial % 2 ? value(random) : small(random)));
            OurNode node(memory_words);
            node.put(0, { 111 });
            node.put(1, array);
            node.put(1 + size, { 222 });
            node.call(standard_native("math.sort"), { 1, static_cast<int16_t>(size) });
            std::sort(array.begin(), array.end());
            EXPECT_EQ(node.get(1, size), array);
            EXPECT_EQ(node.variables[0], 111);
            EXPECT_EQ(node.variables[1 + size], 222);
        }
}

TEST(NativeMath, RandFollowsTheLinearCongruentialGenerator)
{
    OurNode node(memory_words);
    uint32_t state = 1234;
    node.vm.random_state = static_cast<uint16_t>(state);
    for (int16_t size : { 5, 0, 17 }) {
        node.call(standard_native("math.rand"), { 0, size });
        for (int i = 0; i < size; ++i) {
            state = (25173 * state + 13849) % 65536;
            EXPECT_EQ(node.variables[i], static_cast<int16_t>(state));
        }
    }
    EXPECT_EQ(node.vm.random_state, state);
}

// --- hostile arguments ------------------------------------------------------

TEST(NativeMath, SpansOutsideTheVariablesStopTheVmAndTouchNothing)
{
    for (const Words &popped : { Words{ 0, 100, int16_t{ memory_words - 100 + 1 } },
                                 Words{ int16_t{ memory_words - 1 }, 0, 2 },
                                 Words{ 0, 100, -1 },
                                 Words{ 0, -1, 1 } }) {
        OurNode node(memory_words);
        for (size_t i = 0; i < node.variables.size(); ++i)
            node.variables[i] = static_cast<int16_t>(i);
        const Words before = node.variables;
        node.call(standard_native("math.copy"), popped);
        EXPECT_TRUE(node.stopped());
        EXPECT_EQ(node.errors.size(), 1u);
        EXPECT_EQ(node.variables, before);
    }
}

TEST(NativeMath, EveryTemplatedNativeDoesNothingForSizeZero)
{
    for (uint16_t n = 0; n < vm_native_count(&nat_standard_table); ++n) {
        const vm_native &native = *vm_native_at(&nat_standard_table, n);
        const auto description = description_of(native);
        bool has_template = false;
        for (const auto &parameter : description.parameters)
            has_template |= parameter.size < 0;
        // Deques need their header; math.dot always writes its scalar dest.
        const std::string name = description.name;
        if (!has_template || name.starts_with("deque.") || name == "math.dot")
            continue;
        OurNode node(memory_words);
        for (size_t i = 0; i < node.variables.size(); ++i)
            node.variables[i] = static_cast<int16_t>(3 * i + 1);
        const Words before = node.variables;
        Words popped;
        for (size_t p = 0; p < description.parameters.size(); ++p)
            popped.push_back(static_cast<int16_t>(10 * p));
        while (popped.size() < vm_native_stack_words(&native))
            popped.push_back(0);
        node.call(native, popped);
        EXPECT_FALSE(node.stopped()) << name;
        EXPECT_EQ(node.variables, before) << name;
    }
}

} // namespace
