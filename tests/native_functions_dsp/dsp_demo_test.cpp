// The sound-direction example (examples/sound-direction.aesl), compiled by
// our compiler for the e-puck with the DSP natives after the standard ones
// (the order the e-puck's table will have) and run on our VM: recordings in
// which one microphone hears a noise burst first must turn the robot
// towards that side, a sound ahead or silence stop it, and a sound behind
// (the back microphone first) turn it round. The arena runs it on the
// firmware's own recordings (tests/arena/sound_test.cpp).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "dsp_node.hpp"
#include "native_functions/nat_dsp.h"
#include "native_functions/nat_standard.h"
#include "tests/compiler/reference_oracle.hpp"
#include "tools/compiler/aesl.hpp"
#include "tools/compiler/compiler.hpp"
#include "tools/compiler/target_presets.hpp"

namespace
{

constexpr uint16_t samples = 32;
constexpr uint16_t local_event_base = 0xFFFE; // first local event (init is 0xFFFF)

// The e-puck target, which exports the DSP natives right after the standard
// ones (robots/epuck/epuck_natives.c).
aseba::TargetDescription epuck_with_dsp()
{
    auto target = aseba::epuck_target();
    static const vm_native_module *const modules[] = { NAT_DSP_MODULES };
    const vm_native_table dsp{ modules, uint16_t(std::size(modules)), nullptr };
    const size_t standard_count = vm_native_count(&nat_standard_table);
    const size_t dsp_count = vm_native_count(&dsp);
    EXPECT_EQ(target.native_functions.size(), standard_count + dsp_count);
    for (size_t i = 0; i < dsp_count && standard_count + i < target.native_functions.size(); ++i)
        EXPECT_EQ(target.native_functions[standard_count + i].name,
                  description_of(*vm_native_at(&dsp, uint16_t(i))).name);
    return target;
}

uint16_t named_address(const aseba::TargetDescription &target, const std::string &name)
{
    uint16_t address = 0;
    for (const auto &variable : target.named_variables) {
        if (variable.name == name)
            return address;
        address = static_cast<uint16_t>(address + variable.size);
    }
    throw std::invalid_argument(name);
}

uint16_t local_event(const aseba::TargetDescription &target, const std::string &name)
{
    for (size_t i = 0; i < target.local_events.size(); ++i)
        if (target.local_events[i].name == name)
            return static_cast<uint16_t>(local_event_base - i);
    throw std::invalid_argument(name);
}

class SoundDirectionDemo : public ::testing::Test
{
  protected:
    void SetUp() override
    {
        std::ifstream file("examples/sound-direction.aesl");
        ASSERT_TRUE(file) << "run from the repository root";
        std::stringstream text;
        text << file.rdbuf();
        const auto project = aseba::read_aesl(text.str());
        ASSERT_TRUE(project.ok) << project.error;
        ASSERT_EQ(project.project.nodes.size(), 1u);
        const auto result =
          aseba::compile(project.project.nodes[0].source, target, project.project.definitions);
        ASSERT_TRUE(result.ok) << result.error.message;
        image = result.bytecode;
        source = project.project.nodes[0].source;
        definitions = project.project.definitions;
    }

    // Runs the demo on a fresh node, puts the recordings in the firmware's
    // variables (mic.samples0 right, 1 left, 2 back) and raises
    // `microphones`; returns the wheel speeds it sets.
    std::pair<int16_t, int16_t> speeds_after(const Words &right,
                                             const Words &left,
                                             const Words &back)
    {
        DspNode node(target.variables_size, target.bytecode_size);
        node.load_and_run_init(image);
        node.vm.flags = 0;
        node.put(named_address(target, "mic.samples0"), right);
        node.put(named_address(target, "mic.samples1"), left);
        node.put(named_address(target, "mic.samples2"), back);
        vm_setup_event(&node.vm, local_event(target, "microphones"));
        vm_run(&node.vm, 0);
        EXPECT_TRUE(node.errors.empty());
        return { node.variables[named_address(target, "leftSpeed")],
                 node.variables[named_address(target, "rightSpeed")] };
    }

    // A noise burst as heard `delay` samples after the right microphone
    // (negative: before).
    Words heard(int delay)
    {
        Words recording(samples);
        for (int n = 0; n < samples; ++n)
            recording[n] = burst[n + 10 - delay];
        return recording;
    }

    aseba::TargetDescription target = epuck_with_dsp();
    std::mt19937 generator{ 31 };
    const Words burst = random_words(generator, samples + 20, -2000, 2000);
    std::vector<uint16_t> image;
    std::string source;
    aseba::CommonDefinitions definitions;
};

TEST_F(SoundDirectionDemo, CompilesWordForWordAsTheReferenceCompilerDoes)
{
    // The reference lays out the size words of templates -1, -2, -3 as the
    // natives pop them (bytecode.md §9); the same bytecode proves both agree.
    std::string why;
    if (!reference::reference_locale_available(&why))
        GTEST_SKIP() << why;
    const auto theirs = reference::compile_with_reference(source, target, definitions);
    ASSERT_TRUE(theirs.ok) << reference::describe(theirs);
    EXPECT_EQ(image, theirs.bytecode);
}

TEST_F(SoundDirectionDemo, TurnsTowardsTheMicrophoneThatHearsFirst)
{
    // The left and right microphones are 3 readings apart at most.
    for (int delay : { 1, 2, 3 }) {
        // Right first: the source is on the right, turn clockwise.
        const auto clockwise = speeds_after(heard(0), heard(delay), heard(1));
        EXPECT_GT(clockwise.first, 0) << delay;
        EXPECT_LT(clockwise.second, 0) << delay;
        // Left first: counter-clockwise, as fast (the speed is proportional).
        const auto counter = speeds_after(heard(0), heard(-delay), heard(1));
        EXPECT_EQ(counter.first, -clockwise.first) << delay;
        EXPECT_EQ(counter.second, -clockwise.second) << delay;
    }
}

TEST_F(SoundDirectionDemo, StopsWhenTheSoundIsAheadOrSilentAndTurnsRoundFromBehind)
{
    // Ahead: left and right together, the back one later.
    EXPECT_EQ(speeds_after(heard(0), heard(0), heard(2)), std::make_pair(int16_t(0), int16_t(0)));
    EXPECT_EQ(speeds_after(Words(samples, 0), Words(samples, 0), Words(samples, 0)),
              std::make_pair(int16_t(0), int16_t(0)));
    // Behind: the back microphone first.
    const auto round = speeds_after(heard(0), heard(0), heard(-2));
    EXPECT_GT(round.first, 0);
    EXPECT_EQ(round.second, -round.first);
}

} // namespace
