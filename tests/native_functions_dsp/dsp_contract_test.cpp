// The contract of the DSP natives with the VM and the tools: descriptions
// that fit the protocol and match the stack layout of bytecode.md §9, calls
// through NATIVE_CALL, and hostile addresses or sizes that stop the VM
// without touching memory outside the variables (run under ASan + UBSan).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "dsp_node.hpp"

namespace
{

const vm_native *const dsp_natives[] = { &dsp_native("dsp.fft"),  &dsp_native("dsp.mag"),
                                         &dsp_native("dsp.fir"),  &dsp_native("dsp.iir"),
                                         &dsp_native("dsp.corr"), &dsp_native("dsp.conv"),
                                         &dsp_native("dsp.peak") };
constexpr size_t protocol_string_limit = 255; // one length byte (protocol.md §5)

TEST(DspDescriptions, FitTheProtocolAndTheStackContract)
{
    const vm_native_module *const modules[] = { NAT_DSP_MODULES };
    const vm_native_table dsp{ modules, uint16_t(std::size(modules)), nullptr };
    ASSERT_EQ(std::size(dsp_natives), size_t(vm_native_count(&dsp)));
    std::set<std::string> names;
    for (const vm_native *native : dsp_natives) {
        const auto description = description_of(*native);
        const std::string name = description.name;
        EXPECT_EQ(name.rfind("dsp.", 0), 0u) << name;
        EXPECT_TRUE(names.insert(name).second) << name << " twice";
        EXPECT_LE(description.description.size(), protocol_string_limit) << name;
        EXPECT_GT(description.description.size(), 20u) << name;

        // bytecode.md §9: one word per parameter, per size-0 parameter and
        // per distinct template id; template ids are -1, -2, ... without gaps.
        size_t any_size = 0;
        std::set<int> templates;
        for (const auto &parameter : description.parameters) {
            EXPECT_LE(parameter.name.size(), protocol_string_limit);
            if (parameter.size == 0)
                ++any_size;
            if (parameter.size < 0)
                templates.insert(parameter.size);
        }
        if (!templates.empty()) {
            EXPECT_EQ(*templates.begin(), -int(templates.size())) << name;
        }
        EXPECT_EQ(vm_native_stack_words(native),
                  description.parameters.size() + any_size + templates.size())
          << name;
    }
}

// Arguments that work for each native on a node of 1000 variables.
std::vector<int16_t> valid_arguments(const vm_native &native)
{
    const std::string name = description_of(native).name;
    if (name == "dsp.fft")
        return { 0, 100, 64 };
    if (name == "dsp.mag")
        return { 0, 100, 200, 64 };
    if (name == "dsp.fir")
        return { 0, 100, 200, 64, 32 };
    if (name == "dsp.iir")
        return { 0, 100, 200, 300, 64 };
    if (name == "dsp.corr" || name == "dsp.conv")
        return { 0, 100, 200, 300, 63, 32, 32 };
    if (name == "dsp.peak")
        return { 0, 1, 100, 64 };
    throw std::invalid_argument(name);
}

TEST(DspHostileArguments, EveryOutOfRangeAddressOrSizeStopsTheVm)
{
    constexpr uint16_t variables_size = 1000;
    for (const vm_native *native : dsp_natives) {
        const auto description = description_of(*native);
        const auto valid = valid_arguments(*native);
        {
            DspNode node(variables_size);
            node.call(*native, valid);
            EXPECT_TRUE(node.errors.empty()) << description.name;
        }
        for (size_t position = 0; position < valid.size(); ++position) {
            for (int16_t hostile : { int16_t(-1),
                                     int16_t(INT16_MIN),
                                     int16_t(INT16_MAX),
                                     int16_t(variables_size + 1) }) {
                DspNode node(variables_size);
                auto arguments = valid;
                arguments[position] = hostile;
                node.call(*native, arguments);
                EXPECT_EQ(node.errors.size(), 1u)
                  << description.name << " argument " << position << " = " << hostile;
                EXPECT_TRUE(node.stopped());
            }
        }
        // An address whose span runs past the end by one word.
        for (size_t position = 0; position < description.parameters.size(); ++position) {
            DspNode node(variables_size);
            auto arguments = valid;
            arguments[position] = static_cast<int16_t>(variables_size - 1);
            node.call(*native, arguments);
            const bool scalar = description.parameters[position].size == 1;
            EXPECT_EQ(node.errors.size(), scalar ? 0u : 1u)
              << description.name << " argument " << position;
        }
    }
}

TEST(DspHostileArguments, EmptyArraysWriteNothing)
{
    // Size words of 0 (hand-made bytecode: the compiler has no empty arrays):
    // dsp.fft refuses them, the others have nothing to compute.
    for (const vm_native *native : dsp_natives) {
        const auto description = description_of(*native);
        auto arguments = valid_arguments(*native);
        for (size_t position = description.parameters.size(); position < arguments.size();
             ++position)
            arguments[position] = 0;
        DspNode node(1000);
        std::fill(node.variables.begin(), node.variables.end(), int16_t(-7));
        node.variables[300] = 0; // a valid shift for dsp.corr and dsp.conv
        const auto before = node.variables;
        node.call(*native, arguments);
        if (native == &dsp_native("dsp.fft")) {
            EXPECT_EQ(node.errors.size(), 1u);
        } else {
            EXPECT_TRUE(node.errors.empty()) << description.name;
        }
        EXPECT_EQ(node.variables, before) << description.name;
    }
}

// Encodings of bytecode.md §3.
uint16_t small_immediate(int16_t value)
{
    return static_cast<uint16_t>(0x1000 | (value & 0x0FFF));
}
uint16_t native_call(uint16_t id)
{
    return static_cast<uint16_t>(0xC000 | id);
}
constexpr uint16_t stop = 0x0000;

// The NATIVE_CALL id of a DSP native in the e-puck's table order.
uint16_t id_of(const vm_native &native)
{
    for (size_t i = 0; i < std::size(dsp_natives); ++i)
        if (dsp_natives[i] == &native)
            return static_cast<uint16_t>(DspNode::first_dsp_id + i);
    throw std::invalid_argument(description_of(native).name);
}

TEST(DspThroughTheVm, CorrelationAndPeakWithTheStackOfBytecodeSpecification)
{
    // corr(d[5] @10, a[3] @20, b[2] @30, shift @40) then peak(i @41, v @42, d):
    // size words pushed first (templates -3, -2, -1), then addresses, last
    // pushed = first popped = &dest.
    DspNode node(64);
    node.put(20, { 1, 2, 3 });
    node.put(30, { 4, 5 });
    node.put(40, { 0 });
    node.run_init({ small_immediate(2),
                    small_immediate(3),
                    small_immediate(5),
                    small_immediate(40),
                    small_immediate(30),
                    small_immediate(20),
                    small_immediate(10),
                    native_call(id_of(dsp_native("dsp.corr"))),
                    small_immediate(5),
                    small_immediate(10),
                    small_immediate(42),
                    small_immediate(41),
                    native_call(id_of(dsp_native("dsp.peak"))),
                    stop });
    EXPECT_TRUE(node.errors.empty());
    EXPECT_EQ(node.vm.sp, -1);
    // Lags -2 ... 2 of sum a[n + lag] b[n], by hand: 0, 1*5, 1*4 + 2*5,
    // 2*4 + 3*5, 3*4.
    EXPECT_EQ(node.get(10, 5), (Words{ 0, 5, 14, 23, 12 }));
    EXPECT_EQ(node.get(41, 2), (Words{ 3, 23 }));
}

TEST(DspThroughTheVm, FftOfAnImpulseIsFlatAndBadSizesReportTheCallPc)
{
    DspNode node(64);
    node.put(0, { 8000, 0, 0, 0, 0, 0, 0, 0 });
    // fft(real @0, imag @8): N, &imag, &real.
    node.run_init({ small_immediate(8),
                    small_immediate(8),
                    small_immediate(0),
                    native_call(id_of(dsp_native("dsp.fft"))),
                    stop });
    EXPECT_TRUE(node.errors.empty());
    EXPECT_EQ(node.vm.sp, -1);
    // X[k] = 8000 for every k, divided by N = 8.
    EXPECT_EQ(node.get(0, 8), Words(8, 1000));
    EXPECT_EQ(node.get(8, 8), Words(8, 0));

    // Size 6: the NATIVE_CALL is word 3 + 3 of the image.
    DspNode refusing(64);
    refusing.run_init({ small_immediate(6),
                        small_immediate(8),
                        small_immediate(0),
                        native_call(id_of(dsp_native("dsp.fft"))),
                        stop });
    ASSERT_EQ(refusing.errors.size(), 1u);
    EXPECT_EQ(refusing.errors[0].kind, DspError::Kind::node_specific);
    EXPECT_EQ(refusing.errors[0].pc, 6);
    EXPECT_TRUE(refusing.stopped());
}

} // namespace
