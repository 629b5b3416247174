// The natives called by our VM from bytecode: the calling convention of
// bytecode.md §9 on the examples the specifications give (compiled by
// upstream), and the pc an error reports.
#include <gtest/gtest.h>

#include <vector>

#include "our_node.hpp"

namespace
{

using Words = std::vector<int16_t>;

// Encodings of bytecode.md §3: opcode in bits 15..12, operand below.
uint16_t small_immediate(uint16_t value)
{
    return static_cast<uint16_t>(0x1000 | value);
}
uint16_t store(uint16_t address)
{
    return static_cast<uint16_t>(0x4000 | address);
}
uint16_t native_call(uint16_t id)
{
    return static_cast<uint16_t>(0xC000 | id);
}
constexpr uint16_t stop = 0x0000;

// An image handling only `init` (0xFFFF), whose code starts at word 3.
std::vector<uint16_t> init_only(const std::vector<uint16_t> &code)
{
    std::vector<uint16_t> image = { 3, 0xFFFF, 3 };
    image.insert(image.end(), code.begin(), code.end());
    return image;
}

TEST(NativesThroughTheVm, MathFillExampleOfLanguageSpecification)
{
    // language.md §8.7: `call math.fill(a, 7)` with a[4] at 36.
    OurNode node(1100);
    node.run_init(init_only({ small_immediate(4),
                              small_immediate(7),
                              store(1059),
                              small_immediate(1059),
                              small_immediate(36),
                              native_call(1),
                              stop }));
    EXPECT_TRUE(node.errors.empty());
    EXPECT_EQ(node.get(36, 4), (Words{ 7, 7, 7, 7 }));
    EXPECT_EQ(node.vm.sp, -1);
}

TEST(NativesThroughTheVm, DequeGetExampleOfBytecodeSpecification)
{
    // bytecode.md §9: deque.get(a, b[0:1], i), a[4] at 36, b at 40, i at 45.
    OurNode node(64);
    node.put(36, { 2, 1, 10, 20 }); // n = 2, j = 1: the deque holds 20, 10
    node.put(45, { 0 });
    node.run_init(init_only({ small_immediate(2),
                              small_immediate(4),
                              small_immediate(45),
                              small_immediate(40),
                              small_immediate(36),
                              native_call(22),
                              stop }));
    EXPECT_TRUE(node.errors.empty());
    EXPECT_EQ(node.get(40, 2), (Words{ 20, 10 }));
    EXPECT_EQ(node.vm.sp, -1);
}

TEST(NativesThroughTheVm, ErrorsReportThePcOfTheNativeCall)
{
    // math.div(d, a, b) with b[1] = 0; the NATIVE_CALL is at word 7.
    OurNode node(64);
    node.put(10, { 8, 9 });
    node.put(20, { 2, 0 });
    node.run_init(init_only({ small_immediate(2),
                              small_immediate(20),
                              small_immediate(10),
                              small_immediate(0),
                              native_call(6),
                              stop }));
    ASSERT_EQ(node.errors.size(), 1u);
    EXPECT_EQ(node.errors[0], (ErrorReport{ ErrorReport::Kind::division_by_zero, 7, 0, 0, {} }));
    EXPECT_EQ(node.variables[0], 4);
    EXPECT_TRUE(node.stopped());
}

} // namespace
