// The sound-direction example (examples/sound-direction.aesl), compiled by
// our compiler for the e-puck with the DSP natives after the standard ones
// (the order the e-puck's table will have) and run on our VM: recordings in
// which one microphone hears a noise burst first must turn the robot
// towards that side, then stop it after the turn.
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
constexpr uint16_t sender = 2;
constexpr uint16_t local_event_base = 0xFFFE; // first local event (init is 0xFFFF)

// The e-puck target, which exports the DSP natives right after the standard
// ones (firmware/epuck_natives.c).
aseba::TargetDescription epuck_with_dsp()
{
    auto target = aseba::epuck_target();
    const vm_native *const natives[] = { NAT_DSP_LIST };
    EXPECT_EQ(target.native_functions.size(), size_t(NAT_STANDARD_COUNT + NAT_DSP_COUNT));
    for (size_t i = 0; i < NAT_DSP_COUNT && NAT_STANDARD_COUNT + i < target.native_functions.size();
         ++i)
        EXPECT_EQ(target.native_functions[NAT_STANDARD_COUNT + i].name,
                  description_of(*natives[i]).name);
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

    // Runs the demo on a fresh node, sends the two recordings, and returns
    // the wheel speeds it sets; `ticks` timer events follow.
    std::pair<int16_t, int16_t> speeds_after(const Words &left, const Words &right, int ticks)
    {
        DspNode node(target.variables_size, target.bytecode_size, samples);
        node.load_and_run_init(image);
        node.vm.flags = 0;
        vm_receive_event(&node.vm, 0, sender, left.data(), samples);
        vm_run(&node.vm, 0);
        vm_receive_event(&node.vm, 1, sender, right.data(), samples);
        vm_run(&node.vm, 0);
        for (int tick = 0; tick < ticks; ++tick) {
            vm_setup_event(&node.vm, local_event(target, "timer"));
            vm_run(&node.vm, 0);
        }
        EXPECT_TRUE(node.errors.empty());
        return { node.variables[named_address(target, "leftSpeed")],
                 node.variables[named_address(target, "rightSpeed")] };
    }

    // A noise burst heard by the left microphone `delay` samples after the
    // right one (negative: before).
    std::pair<Words, Words> recordings(int delay)
    {
        std::mt19937 generator(31);
        const auto burst = random_words(generator, samples + 20, -2000, 2000);
        Words left(samples), right(samples);
        for (int n = 0; n < samples; ++n) {
            right[n] = burst[n + 10];
            left[n] = burst[n + 10 - delay];
        }
        return { left, right };
    }

    aseba::TargetDescription target = epuck_with_dsp();
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
    for (int delay : { 1, 3, 6 }) {
        // Right first: the source is on the right, turn clockwise.
        const auto [right_left, right_right] = recordings(delay);
        const auto clockwise = speeds_after(right_left, right_right, 0);
        EXPECT_GT(clockwise.first, 0) << delay;
        EXPECT_LT(clockwise.second, 0) << delay;
        // Left first: counter-clockwise, as fast (the speed is proportional).
        const auto [left_left, left_right] = recordings(-delay);
        const auto counter = speeds_after(left_left, left_right, 0);
        EXPECT_EQ(counter.first, -clockwise.first) << delay;
        EXPECT_EQ(counter.second, -clockwise.second) << delay;
    }
    // In front (no delay): no turn.
    const auto [left, right] = recordings(0);
    EXPECT_EQ(speeds_after(left, right, 0), std::make_pair(int16_t(0), int16_t(0)));
}

TEST_F(SoundDirectionDemo, StopsAfterTheTurnAndIgnoresSilence)
{
    const auto [left, right] = recordings(3);
    EXPECT_NE(speeds_after(left, right, 4).first, 0);
    EXPECT_EQ(speeds_after(left, right, 5), std::make_pair(int16_t(0), int16_t(0)));
    EXPECT_EQ(speeds_after(Words(samples, 0), Words(samples, 0), 0),
              std::make_pair(int16_t(0), int16_t(0)));
}

} // namespace
