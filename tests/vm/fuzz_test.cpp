// Robustness: random bytecode images (random words, and mutations of valid
// programs) run with budgets between random debug commands and incoming
// events, on random memory sizes down to 0. Under the sanitizer build any
// out-of-bounds access or undefined behaviour aborts the test; the driver
// checks the VM's invariants and the guard words around its arrays.

#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>

#include <gtest/gtest.h>

#include "tests/support/assembler.hpp"
#include "tests/vm/fuzz_driver.hpp"
#include "tests/vm/random_program.hpp"

extern "C" {
#include "vm/vm_opcodes.h"
}

namespace
{

using vm_tests::FuzzCase;

constexpr unsigned CASE_COUNT = 100000;
constexpr unsigned VALID_PROGRAM_POOL = 64;
constexpr uint32_t SEED = 4242;

class CaseMaker
{
  public:
    CaseMaker()
      : random_(SEED)
    {
        vm_tests::RandomProgramOptions options;
        options.statements_per_block = 3;
        options.subroutines = 2;
        for (unsigned i = 0; i < VALID_PROGRAM_POOL; i++)
            pool_.push_back(
              test_support::assemble(vm_tests::random_program(random_, options)).words);
    }

    FuzzCase next(bool mutate_valid)
    {
        FuzzCase fuzz_case;
        // Valid programs: a third as they are, a third with values changed
        // (which the verifier accepts when they stay in range: the run loop,
        // which trusts it, meets odd values), a third broken anywhere.
        if (!mutate_valid)
            fuzz_case.image = random_image();
        else if (chance(33))
            fuzz_case.image = pool_[uniform(0, VALID_PROGRAM_POOL - 1)];
        else if (chance(50))
            fuzz_case.image = program_with_new_values();
        else
            fuzz_case.image = mutated_program();
        static const uint16_t variable_sizes[] = { 0, 1, 2, 3, 8, 34, 64, 128, 300 };
        static const uint16_t stack_sizes[] = { 0, 1, 2, 3, 8, 32 };
        static const uint16_t args_sizes[] = { 0, 1, 8, 32, 300 };
        uint16_t image_size = static_cast<uint16_t>(fuzz_case.image.size());
        const uint16_t bytecode_sizes[] = { 0,
                                            1,
                                            3,
                                            image_size,
                                            image_size,
                                            image_size,
                                            image_size,
                                            static_cast<uint16_t>(image_size + 3),
                                            static_cast<uint16_t>(image_size / 2),
                                            256 };
        fuzz_case.sizes.bytecode = pick(bytecode_sizes);
        fuzz_case.sizes.variables = mutate_valid && chance(70) ? 128 : pick(variable_sizes);
        fuzz_case.sizes.stack = mutate_valid && chance(70) ? 32 : pick(stack_sizes);
        fuzz_case.sizes.args = pick(args_sizes);
        fuzz_case.commands.resize(uniform(0, 40));
        for (uint8_t &byte : fuzz_case.commands)
            byte = static_cast<uint8_t>(uniform(0, 255));
        return fuzz_case;
    }

  private:
    int uniform(int low, int high)
    {
        return std::uniform_int_distribution<int>(low, high)(random_);
    }
    bool chance(int percent)
    {
        return uniform(1, 100) <= percent;
    }
    template<typename T, size_t N>
    T pick(const T (&values)[N])
    {
        return values[uniform(0, N - 1)];
    }

    // A plausible table (so that handlers run) then words of any opcode.
    std::vector<uint16_t> random_image()
    {
        size_t length = static_cast<size_t>(uniform(1, 48));
        std::vector<uint16_t> image;
        if (chance(80)) {
            static const uint16_t events[] = { 0xFFFF, 0xFFFE, 0, 1, 2 };
            int event_count = uniform(0, 3);
            int table_size = 2 * event_count + 1;
            image.push_back(static_cast<uint16_t>(chance(90) ? table_size : uniform(0, 65535)));
            for (int i = 0; i < event_count; i++) {
                image.push_back(i == 0 && chance(80) ? VM_EVENT_INIT : pick(events));
                image.push_back(
                  static_cast<uint16_t>(chance(80) ? table_size + uniform(0, 6)
                                                   : uniform(0, static_cast<int>(length) + 8)));
            }
        }
        while (image.size() < length) {
            // Pushes and emits more often than the rest: stacks fill, emits run.
            static const uint16_t opcodes[] = { 0x0, 0x1, 0x1, 0x1, 0x2, 0x3, 0x3, 0x4,
                                                0x5, 0x6, 0x7, 0x8, 0x8, 0x9, 0xA, 0xB,
                                                0xB, 0xB, 0xC, 0xD, 0xE, 0xF };
            uint16_t opcode = pick(opcodes);
            uint16_t operand =
              static_cast<uint16_t>(chance(70) ? uniform(0, 40) : uniform(0, 0xFFF));
            if (opcode == 0x7 || opcode == 0x8 || opcode == 0xA)
                operand = static_cast<uint16_t>(chance(90) ? uniform(0, 20) | (uniform(0, 3) << 8)
                                                           : operand);
            uint16_t word = static_cast<uint16_t>(opcode << 12 | operand);
            image.push_back(word);
            // Usually as many operand words as the opcode has, small ones.
            int extra = chance(85) ? vm_instruction_words(word) - 1 : uniform(0, 2);
            for (int i = 0; i < extra; i++)
                image.push_back(
                  static_cast<uint16_t>(chance(80) ? uniform(-4, 40) : uniform(0, 65535)));
        }
        return image;
    }

    // A valid program whose instructions keep their kinds and lengths but
    // get other operands: addresses, sizes, immediates, operators, natives,
    // event ids; mostly in range, sometimes just past it, so that a verifier
    // that let one through would have the loop meet it.
    std::vector<uint16_t> program_with_new_values()
    {
        std::vector<uint16_t> image = pool_[uniform(0, VALID_PROGRAM_POOL - 1)];
        std::vector<size_t> starts;
        for (size_t pc = image[0]; pc < image.size(); pc += vm_instruction_words(image[pc]))
            starts.push_back(pc);
        const int variables = vm_tests::RandomProgramLayout::VARIABLES;
        const int beyond = chance(90) ? 0 : 8; // how far past its range a value may go
        for (int m = uniform(1, 6); m > 0; m--) {
            size_t pc =
              starts[static_cast<size_t>(uniform(0, static_cast<int>(starts.size()) - 1))];
            uint16_t opcode = image[pc] >> VM_OPCODE_SHIFT;
            auto set_operand = [&](int operand) {
                image[pc] = static_cast<uint16_t>(opcode << 12 | (operand & VM_OPERAND_MASK));
            };
            switch (opcode) {
            case VM_OP_SMALL_IMMEDIATE: set_operand(uniform(0, 0xFFF)); break;
            case VM_OP_NATIVE_CALL: // the harness' table has 4 natives
                set_operand(uniform(0, test_support::NATIVE_YIELD - 1 + beyond));
                break;
            case VM_OP_EMIT:
                set_operand(uniform(0, 0xFFF));
                image[pc + 1] = static_cast<uint16_t>(uniform(0, variables + beyond));
                image[pc + 2] = static_cast<uint16_t>(
                  beyond ? uniform(VM_MAX_EVENT_WORDS - 4, VM_MAX_EVENT_WORDS + 4)
                         : uniform(0, 40));
                break;
            case VM_OP_LOAD:
            case VM_OP_STORE: set_operand(uniform(0, variables - 1 + beyond)); break;
            case VM_OP_LARGE_IMMEDIATE:
                image[pc + 1] = static_cast<uint16_t>(interesting_word());
                break;
            case VM_OP_LOAD_INDIRECT:
            case VM_OP_STORE_INDIRECT: {
                int base = uniform(0, variables);
                set_operand(base);
                image[pc + 1] = static_cast<uint16_t>(uniform(0, variables - base + beyond));
                break;
            }
            case VM_OP_UNARY_ARITHMETIC:
                set_operand(uniform(0, VM_UNARY_NOT - 1 + (beyond ? 2 : 0)));
                break;
            case VM_OP_BINARY_ARITHMETIC:
            case VM_OP_CONDITIONAL_BRANCH:
                set_operand(uniform(0, 3) << 8 |
                            uniform(0, beyond ? 0xFF : VM_BINARY_OPERATOR_COUNT - 1));
                break;
            default: break;
            }
        }
        return image;
    }

    int interesting_word()
    {
        static const int words[] = { -32768, -32767, -1, 0, 1, 2, 15, 16, 17, 31, 32, 32767 };
        return chance(50) ? words[uniform(0, std::size(words) - 1)] : uniform(-32768, 32767);
    }

    std::vector<uint16_t> mutated_program()
    {
        std::vector<uint16_t> image = pool_[uniform(0, VALID_PROGRAM_POOL - 1)];
        int mutations = uniform(1, 4);
        for (int m = 0; m < mutations && !image.empty(); m++) {
            size_t at = static_cast<size_t>(uniform(0, static_cast<int>(image.size()) - 1));
            switch (uniform(0, 4)) {
            case 0: image[at] ^= static_cast<uint16_t>(1u << uniform(0, 15)); break;
            case 1: image[at] = static_cast<uint16_t>(uniform(0, 65535)); break;
            case 2: image.resize(at + 1); break;
            case 3:
                image.insert(image.begin() + static_cast<long>(at),
                             static_cast<uint16_t>(uniform(0, 65535)));
                break;
            default: image.erase(image.begin() + static_cast<long>(at)); break;
            }
        }
        return image;
    }

    std::mt19937 random_;
    std::vector<std::vector<uint16_t>> pool_;
};

TEST(VmFuzz, RandomImagesAndCommandsKeepTheVmSafe)
{
    CaseMaker maker;
    vm_tests::FuzzStats stats;
    unsigned failures = 0;
    for (unsigned n = 0; n < CASE_COUNT && failures < 5; n++) {
        FuzzCase fuzz_case = maker.next(n % 2 == 1);
        std::string problem = vm_tests::run_fuzz_case(fuzz_case, &stats);
        if (!problem.empty()) {
            failures++;
            ADD_FAILURE() << "case " << n << ": " << problem;
        }
    }
    using test_support::VmMessage;
    std::cout << stats.runs << " runs (" << stats.run_step_comparisons
              << " compared with vm_step), messages:";
    for (unsigned kind = 0; kind <= VmMessage::NODE_ERROR; kind++)
        std::cout << " " << stats.messages[kind];
    std::cout << " (emit, state, killed, array, division, node error); " << stats.accepted_uploads
              << " of " << stats.uploads << " images accepted by the verifier\n";
    for (unsigned kind = 0; kind <= VmMessage::NODE_ERROR; kind++)
        EXPECT_GT(stats.messages[kind], CASE_COUNT / 100) << "message kind " << kind;
    // Enough images pass the verifier for the run loop, which trusts it, to
    // be fuzzed too, and enough are refused for the verifier to be.
    EXPECT_GT(stats.accepted_uploads, stats.uploads / 10);
    EXPECT_LT(stats.accepted_uploads, stats.uploads * 4 / 5);
}

// The byte decoder of the libFuzzer target, on inputs of every length.
TEST(VmFuzz, BytesDecodeIntoCasesThatRun)
{
    std::mt19937 random(SEED);
    for (size_t size = 0; size < 600; size++) {
        std::vector<uint8_t> bytes(size);
        for (uint8_t &byte : bytes)
            byte = static_cast<uint8_t>(random());
        FuzzCase fuzz_case = vm_tests::fuzz_case_from_bytes(bytes.data(), bytes.size());
        EXPECT_EQ(vm_tests::run_fuzz_case(fuzz_case), "") << "input of " << size << " bytes";
    }
}

} // namespace

// Inputs the libFuzzer target once found (tests/fuzz/regressions/vm/) stay
// fixed: each must now run with every invariant kept.
TEST(VmFuzz, FoundInputsStayFixed)
{
    const std::filesystem::path folder = "tests/fuzz/regressions/vm";
    ASSERT_TRUE(std::filesystem::is_directory(folder)) << "run the tests from the repository root";
    unsigned inputs = 0;
    for (const auto &entry : std::filesystem::directory_iterator(folder)) {
        std::ifstream file(entry.path(), std::ios::binary);
        std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)), {});
        vm_tests::FuzzCase fuzz_case = vm_tests::fuzz_case_from_bytes(bytes.data(), bytes.size());
        EXPECT_EQ(vm_tests::run_fuzz_case(fuzz_case), "") << entry.path();
        inputs++;
    }
    EXPECT_GT(inputs, 0u);
}
