// The deque natives against a model (a std::deque of words) of the logical
// content, with the error rules of language.md §13.2: every error stops the
// VM with ARRAY_ACCESS_OUT_OF_BOUNDS(pc, length of the deque, offending index
// or n + S) and leaves memory untouched.
#include <gtest/gtest.h>

#include <deque>
#include <optional>
#include <random>
#include <vector>

#include "our_node.hpp"

namespace
{

using Words = std::vector<int16_t>;

constexpr uint16_t memory_words = 256;
constexpr uint16_t deque_address = 10;
constexpr uint16_t tuple_address = 100;
constexpr uint16_t index_address = 200;
constexpr uint16_t length_address = 201;
constexpr uint16_t size_address = 202;

// The logical content of the deque array at `address` of `length` words,
// decoded by the layout of the specification: Q[0] = n, Q[1] = j, element p
// at Q[2 + (j + p) mod K].
std::deque<int16_t> decode(const OurNode &node, uint16_t address, uint16_t length)
{
    const int capacity = length - 2;
    const int count = node.variables[address];
    const int start = node.variables[address + 1];
    std::deque<int16_t> content;
    for (int p = 0; p < count; ++p)
        content.push_back(node.variables[address + 2 + (start + p) % capacity]);
    return content;
}

ErrorReport out_of_bounds(uint16_t length, int index)
{
    return {
        ErrorReport::Kind::array_access, OurNode::call_pc, length, static_cast<uint16_t>(index), {}
    };
}

class DequeModelTest : public ::testing::TestWithParam<int>
{
};

// Random operations on deques of every capacity from 1 to 9, compared after
// each with the model.
TEST_P(DequeModelTest, RandomOperationsMatchTheModel)
{
    const int capacity = GetParam();
    const auto length = static_cast<uint16_t>(capacity + 2);
    std::mt19937 random(1000 + capacity);
    std::uniform_int_distribution<int> operation_of(0, 8);
    std::uniform_int_distribution<int> tuple_size_of(0, 4);
    std::uniform_int_distribution<int> index_of(-2, capacity + 1);
    std::uniform_int_distribution<int> value_of(-32768, 32767);

    OurNode node(memory_words);
    std::deque<int16_t> model;
    for (int step = 0; step < 3000; ++step) {
        const int operation = operation_of(random);
        const int tuple_size = tuple_size_of(random);
        int index = index_of(random);
        const int n = static_cast<int>(model.size());
        // Inserting past n makes unspecified words part of the deque (as
        // upstream): that case is left to the reference comparison.
        if (operation == 3 && index > n)
            index = n;
        Words tuple;
        for (int i = 0; i < tuple_size; ++i)
            tuple.push_back(static_cast<int16_t>(value_of(random)));
        const int erase_length = tuple_size - 1; // -1 ... 3
        node.put(tuple_address, tuple);
        node.put(index_address, { static_cast<int16_t>(index) });
        node.put(length_address, { static_cast<int16_t>(erase_length) });
        const auto tuple_word = static_cast<int16_t>(tuple_size);
        const auto length_word = static_cast<int16_t>(length);
        const Words before = node.variables;
        node.errors.clear();

        std::optional<ErrorReport> expected_error;
        Words expected_tuple = tuple;
        const bool bad_index = index < 0 || index > capacity - 1;
        switch (operation) {
        case 0: // size
            node.call(standard_native("deque.size"), { deque_address, size_address, length_word });
            EXPECT_EQ(node.variables[size_address], n);
            break;
        case 1: // get
            node.call(standard_native("deque.get"),
                      { deque_address, tuple_address, index_address, length_word, tuple_word });
            if (bad_index)
                expected_error = out_of_bounds(length, index);
            else if (index + tuple_size > n)
                expected_error = out_of_bounds(length, index + tuple_size);
            else
                expected_tuple.assign(model.begin() + index, model.begin() + index + tuple_size);
            break;
        case 2: // set
            node.call(standard_native("deque.set"),
                      { deque_address, tuple_address, index_address, length_word, tuple_word });
            if (bad_index)
                expected_error = out_of_bounds(length, index);
            else if (index + tuple_size > n)
                expected_error = out_of_bounds(length, index + tuple_size);
            else
                std::copy(tuple.begin(), tuple.end(), model.begin() + index);
            break;
        case 3: // insert
            node.call(standard_native("deque.insert"),
                      { deque_address, tuple_address, index_address, length_word, tuple_word });
            if (bad_index)
                expected_error = out_of_bounds(length, index);
            else if (tuple_size > capacity - n)
                expected_error = out_of_bounds(length, n + tuple_size);
            else
                model.insert(model.begin() + index, tuple.begin(), tuple.end());
            break;
        case 4: // erase
            node.call(standard_native("deque.erase"),
                      { deque_address, index_address, length_address, length_word });
            if (bad_index)
                expected_error = out_of_bounds(length, index);
            else if (erase_length < 0 || index + erase_length > n)
                expected_error = out_of_bounds(length, index + erase_length);
            else
                model.erase(model.begin() + index, model.begin() + index + erase_length);
            break;
        case 5: // push_front
        case 6: // push_back
            node.call(operation == 5 ? standard_native("deque.push_front")
                                     : standard_native("deque.push_back"),
                      { deque_address, tuple_address, length_word, tuple_word });
            if (tuple_size > capacity - n)
                expected_error = out_of_bounds(length, n + tuple_size);
            else
                model.insert(
                  operation == 5 ? model.begin() : model.end(), tuple.begin(), tuple.end());
            break;
        case 7: // pop_front
        case 8: // pop_back
            node.call(operation == 7 ? standard_native("deque.pop_front")
                                     : standard_native("deque.pop_back"),
                      { deque_address, tuple_address, length_word, tuple_word });
            if (tuple_size > n) {
                expected_error = out_of_bounds(length, tuple_size);
            } else if (operation == 7) {
                expected_tuple.assign(model.begin(), model.begin() + tuple_size);
                model.erase(model.begin(), model.begin() + tuple_size);
            } else {
                expected_tuple.assign(model.end() - tuple_size, model.end());
                model.erase(model.end() - tuple_size, model.end());
            }
            break;
        }
        SCOPED_TRACE("step " + std::to_string(step) + " operation " + std::to_string(operation));
        if (expected_error) {
            EXPECT_TRUE(node.stopped());
            ASSERT_EQ(node.errors, std::vector<ErrorReport>{ *expected_error });
            ASSERT_EQ(node.variables, before);
        } else {
            ASSERT_FALSE(node.stopped());
            ASSERT_TRUE(node.errors.empty());
            ASSERT_EQ(decode(node, deque_address, length), model);
            ASSERT_EQ(node.get(tuple_address, tuple_size), expected_tuple);
            ASSERT_GE(node.variables[deque_address + 1], 0);
            ASSERT_LT(node.variables[deque_address + 1], capacity);
        }
        // Nothing outside the deque and the tuple may change.
        for (uint16_t a = 0; a < memory_words; ++a) {
            const bool in_deque = a >= deque_address && a < deque_address + length;
            const bool in_tuple = a >= tuple_address && a < tuple_address + tuple_size;
            if (!in_deque && !in_tuple && a != size_address) {
                ASSERT_EQ(node.variables[a], before[a]) << "address " << a;
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Capacities, DequeModelTest, ::testing::Range(1, 10));

TEST(Deque, InsertNearTheFrontMovesTheRightWords)
{
    // language.md §13.2: upstream gives [?, 99, 22, 33, 44] here.
    OurNode node(memory_words);
    node.put(deque_address, { 4, 0, 11, 22, 33, 44, 0, 0 });
    node.put(tuple_address, { 99 });
    node.put(index_address, { 1 });
    node.call(standard_native("deque.insert"),
              { deque_address, tuple_address, index_address, 8, 1 });
    ASSERT_FALSE(node.stopped());
    EXPECT_EQ(decode(node, deque_address, 8), (std::deque<int16_t>{ 11, 99, 22, 33, 44 }));
}

TEST(Deque, EraseOfNothingChangesNothing)
{
    OurNode node(memory_words);
    node.put(deque_address, { 4, 0, 11, 22, 33, 44, 0, 0 });
    node.put(index_address, { 0 });
    node.put(length_address, { 0 });
    const Words before = node.variables;
    node.call(standard_native("deque.erase"), { deque_address, index_address, length_address, 8 });
    EXPECT_FALSE(node.stopped());
    EXPECT_EQ(node.variables, before);
}

TEST(Deque, PhysicalLayoutFollowsTheSpecification)
{
    // Pushing to the front of an empty deque moves j back around the ring.
    OurNode node(memory_words);
    node.put(tuple_address, { 7, 8 });
    node.call(standard_native("deque.push_front"), { deque_address, tuple_address, 6, 2 });
    EXPECT_EQ(node.get(deque_address, 6), (Words{ 2, 0, 7, 8, 0, 0 }));
    node.put(tuple_address, { 5 });
    node.call(standard_native("deque.push_front"), { deque_address, tuple_address, 6, 1 });
    // Index 0 < n/2 = 1: the front moves back around the ring, j = 3.
    EXPECT_EQ(node.get(deque_address, 6), (Words{ 3, 3, 7, 8, 0, 5 }));
}

TEST(Deque, MalformedDequesAreRefused)
{
    struct Case {
        Words header;
        int16_t length;
        int reported_index;
    };
    for (const Case &c : { Case{ {}, 1, 1 },
                           Case{ { -1, 0 }, 6, -1 },
                           Case{ { 5, 0 }, 6, 5 },
                           Case{ { 0, 4 }, 6, 4 },
                           Case{ { 0, -3 }, 6, -3 },
                           Case{ { 1, 1 }, 2, 1 } }) {
        OurNode node(memory_words);
        node.put(deque_address, c.header);
        const Words before = node.variables;
        node.call(standard_native("deque.push_back"),
                  { deque_address, tuple_address, c.length, 0 });
        EXPECT_TRUE(node.stopped());
        ASSERT_EQ(node.errors.size(), 1u);
        EXPECT_EQ(node.errors[0], out_of_bounds(static_cast<uint16_t>(c.length), c.reported_index));
        EXPECT_EQ(node.variables, before);
    }
    // Capacity 0 is a deque that can only hold nothing.
    OurNode node(memory_words);
    node.call(standard_native("deque.push_back"), { deque_address, tuple_address, 2, 0 });
    EXPECT_FALSE(node.stopped());
    node.call(standard_native("deque.pop_front"), { deque_address, tuple_address, 2, 0 });
    EXPECT_FALSE(node.stopped());
    node.call(standard_native("deque.push_back"), { deque_address, tuple_address, 2, 1 });
    EXPECT_EQ(node.errors, std::vector<ErrorReport>{ out_of_bounds(2, 1) });
    // deque.size of an empty array has no n to read.
    OurNode empty(memory_words);
    empty.call(standard_native("deque.size"), { deque_address, size_address, 0 });
    EXPECT_EQ(empty.errors, std::vector<ErrorReport>{ out_of_bounds(0, 0) });
}

// Random words for every native: whatever the addresses, sizes and deque
// headers, a call either succeeds silently or stops with one error, and the
// sanitizers see no bad access.
TEST(NativeRobustness, RandomArgumentsNeverMisbehave)
{
    std::mt19937 random(99);
    std::uniform_int_distribution<int> any_word(-32768, 32767);
    std::uniform_int_distribution<int> small_word(-3, 40);
    std::uniform_int_distribution<int> coin(0, 3);
    OurNode node(64);
    for (int trial = 0; trial < 30000; ++trial) {
        const vm_native &native =
          *vm_native_at(&nat_standard_table, trial % vm_native_count(&nat_standard_table));
        for (auto &word : node.variables)
            word = static_cast<int16_t>(coin(random) == 0 ? any_word(random) : small_word(random));
        Words popped;
        for (int w = 0; w < vm_native_stack_words(&native); ++w)
            popped.push_back(
              static_cast<int16_t>(coin(random) == 0 ? any_word(random) : small_word(random)));
        node.errors.clear();
        node.call(native, popped);
        ASSERT_EQ(node.errors.size(), node.stopped() ? 1u : 0u) << description_of(native).name;
    }
}

} // namespace
