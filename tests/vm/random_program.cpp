#include "tests/vm/random_program.hpp"

#include <sstream>

#include "tests/support/assembler.hpp"
#include "tests/support/vm_harness.hpp"

namespace vm_tests
{

namespace
{

// Variables: 10 .. 99 may be written; arrays live inside that range; loop
// counters take 100 .. 127, one per loop, so no statement disturbs them.
constexpr int FIRST_WRITABLE = 10;
constexpr int LAST_WRITABLE = 99;
constexpr int FIRST_COUNTER = 100;
constexpr int MAX_EXPRESSION_DEPTH = 4;
constexpr int MAX_BLOCK_DEPTH = 2;

struct Array {
    int base;
    int size;
};
const Array arrays[] = { { 40, 8 }, { 48, 16 }, { 64, 3 }, { 2, 8 }, { 90, 1 } };

class Generator
{
  public:
    Generator(std::mt19937 &random, const RandomProgramOptions &options)
      : random_(random)
      , options_(options)
    {
    }
    std::string program();

  private:
    int uniform(int low, int high)
    {
        return std::uniform_int_distribution<int>(low, high)(random_);
    }
    bool chance(int percent)
    {
        return uniform(1, 100) <= percent;
    }
    std::string label()
    {
        return "L" + std::to_string(next_label_++);
    }

    int interesting_value();
    void expression(int depth);
    void index_expression(const Array &array);
    void statement(int depth, int routine);
    void block(int depth, int routine, unsigned count);

    std::mt19937 &random_;
    RandomProgramOptions options_;
    std::ostringstream out_;
    int next_label_ = 0;
    int next_counter_ = FIRST_COUNTER;
};

int Generator::interesting_value()
{
    static const int values[] = { -32768, -32767, -2049, -2048, -2047, -256, -17,  -16,
                                  -15,    -1,     0,     1,     2,     15,   16,   17,
                                  31,     32,     33,    255,   2047,  2048, 4096, 32767 };
    if (chance(60))
        return values[uniform(0, std::size(values) - 1)];
    return uniform(-32768, 32767);
}

void Generator::expression(int depth)
{
    int kind = depth >= MAX_EXPRESSION_DEPTH ? uniform(0, 2) : uniform(0, 9);
    switch (kind) {
    case 0:
        out_ << "SMALL_IMMEDIATE " << (chance(50) ? uniform(-3, 3) : uniform(-2048, 2047)) << "\n";
        break;
    case 1: out_ << "LARGE_IMMEDIATE " << interesting_value() << "\n"; break;
    case 2: out_ << "LOAD " << uniform(0, RandomProgramLayout::VARIABLES - 1) << "\n"; break;
    case 3: {
        const Array &array = arrays[uniform(0, std::size(arrays) - 1)];
        index_expression(array);
        out_ << "LOAD_INDIRECT " << array.base << " " << array.size << "\n";
        break;
    }
    case 4:
        expression(depth + 1);
        out_ << "UNARY_ARITHMETIC " << test_support::unary_operator_names()[uniform(0, 2)] << "\n";
        break;
    default: {
        expression(depth + 1);
        expression(depth + 1);
        const auto &names = test_support::binary_operator_names();
        out_ << "BINARY_ARITHMETIC " << names[uniform(0, names.size() - 1)] << "\n";
    }
    }
}

// Mostly in range; sometimes any value, which is usually out of range.
void Generator::index_expression(const Array &array)
{
    if (chance(85))
        out_ << "SMALL_IMMEDIATE " << uniform(0, array.size - 1) << "\n";
    else if (chance(50))
        out_ << "SMALL_IMMEDIATE " << (chance(50) ? array.size : -1) << "\n";
    else
        expression(MAX_EXPRESSION_DEPTH - 1);
}

void Generator::statement(int depth, int routine)
{
    const auto &names = test_support::binary_operator_names();
    int kind = uniform(0, 11);
    if (depth >= MAX_BLOCK_DEPTH && kind >= 5 && kind <= 7)
        kind = 0;
    switch (kind) {
    case 0:
    case 1:
        expression(0);
        out_ << "STORE " << uniform(FIRST_WRITABLE, LAST_WRITABLE) << "\n";
        break;
    case 2: {
        const Array &array = arrays[uniform(0, 2)];
        expression(1);
        index_expression(array);
        out_ << "STORE_INDIRECT " << array.base << " " << array.size << "\n";
        break;
    }
    case 3: {
        int length = chance(80) ? uniform(0, 6) : uniform(0, 40);
        int address = uniform(0, RandomProgramLayout::VARIABLES - length);
        out_ << "EMIT " << (chance(70) ? uniform(0, 3) : uniform(0, 4095)) << " " << address << " "
             << length << "\n";
        break;
    }
    case 4: { // routine k calls only subroutines below k: no recursion
        int highest = routine == 0 ? static_cast<int>(options_.subroutines) : routine - 1;
        if (highest >= 1)
            out_ << "SUB_CALL sub" << uniform(1, highest) << "\n";
        break;
    }
    case 5:
    case 6: { // if / when, with an optional else
        std::string otherwise = label(), end = label();
        expression(1);
        expression(1);
        bool is_when = chance(40);
        out_ << "CONDITIONAL_BRANCH " << names[uniform(0, names.size() - 1)] << " " << otherwise
             << (is_when ? " when" : "") << "\n";
        block(depth + 1, routine, uniform(1, 3));
        if (chance(40)) {
            out_ << "JUMP " << end << "\n" << otherwise << ":\n";
            block(depth + 1, routine, uniform(1, 3));
            out_ << end << ":\n";
        } else {
            out_ << otherwise << ":\n";
        }
        break;
    }
    case 7: { // a loop of 0 .. 5 iterations on its own counter
        if (next_counter_ >= RandomProgramLayout::VARIABLES)
            break;
        int counter = next_counter_++;
        std::string top = label(), end = label();
        out_ << "SMALL_IMMEDIATE 0\nSTORE " << counter << "\n"
             << top << ":\nLOAD " << counter << "\nSMALL_IMMEDIATE " << uniform(0, 5) << "\n"
             << "CONDITIONAL_BRANCH SMALLER_THAN " << end << "\n";
        block(depth + 1, routine, uniform(1, 3));
        out_ << "LOAD " << counter << "\nSMALL_IMMEDIATE 1\nBINARY_ARITHMETIC ADD\nSTORE "
             << counter << "\nJUMP " << top << "\n"
             << end << ":\n";
        break;
    }
    case 8:
    case 9:
        if (!options_.natives)
            break;
        if (chance(50)) { // subtract(dest, a, b)
            out_ << "SMALL_IMMEDIATE " << uniform(0, RandomProgramLayout::VARIABLES - 1) << "\n"
                 << "SMALL_IMMEDIATE " << uniform(0, RandomProgramLayout::VARIABLES - 1) << "\n"
                 << "SMALL_IMMEDIATE " << uniform(FIRST_WRITABLE, LAST_WRITABLE) << "\n"
                 << "NATIVE_CALL " << test_support::NATIVE_SUBTRACT << "\n";
        } else { // fill(dest, value, size)
            int size = uniform(0, 8);
            out_ << "SMALL_IMMEDIATE " << size << "\n"
                 << "SMALL_IMMEDIATE " << uniform(0, RandomProgramLayout::VARIABLES - 1) << "\n"
                 << "SMALL_IMMEDIATE " << uniform(FIRST_WRITABLE, LAST_WRITABLE + 1 - size) << "\n"
                 << "NATIVE_CALL " << test_support::NATIVE_FILL << "\n";
        }
        break;
    case 10:
        if (options_.failing_native && chance(15))
            out_ << "NATIVE_CALL " << test_support::NATIVE_FAIL << "\n";
        break;
    default:
        expression(2);
        out_ << "STORE " << uniform(FIRST_WRITABLE, LAST_WRITABLE) << "\n";
        break;
    }
}

void Generator::block(int depth, int routine, unsigned count)
{
    for (unsigned i = 0; i < count; i++)
        statement(depth, routine);
}

std::string Generator::program()
{
    const char *const handlers[] = { "init", "0", "1", "0xFFFE" };
    for (int i = 0; i < 4; i++)
        out_ << "event " << handlers[i] << " handler" << i << "\n";
    // The table is 9 words; upstream's reset walk starts at 2 * 9 + 1 = 19:
    // 10 one-word STOPs put that start on an instruction boundary and keep
    // every branch after it.
    const int table_words = 9;
    for (int i = 0; i < table_words + 1; i++)
        out_ << "STOP\n";
    for (int i = 0; i < 4; i++) {
        out_ << "handler" << i << ":\n";
        block(0, 0, uniform(1, options_.statements_per_block));
        out_ << "STOP\n";
    }
    for (unsigned k = 1; k <= options_.subroutines; k++) {
        out_ << "sub" << k << ":\n";
        block(0, static_cast<int>(k), uniform(0, options_.statements_per_block / 2));
        out_ << "SUB_RET\n";
    }
    return out_.str();
}

} // namespace

std::string random_program(std::mt19937 &random, const RandomProgramOptions &options)
{
    return Generator(random, options).program();
}

} // namespace vm_tests
