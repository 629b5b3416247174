// Builds random programs top-down from the grammar of language.md §4. Sizes
// are chosen first and every sub-expression is generated with the size it
// must have (§6), so vector rules hold by construction. Values of constant
// sub-expressions are tracked with the compiler's folding arithmetic (§9
// rule 1) to keep constant indexes in bounds and constant divisors non-zero.

#include "program_generator.hpp"

#include <algorithm>
#include <cctype>
#include <climits>

namespace compiler_tests
{

namespace
{

// Shape of generated programs: small enough to stay far from the target's
// limits, large enough to combine every construct.
constexpr int max_expression_depth = 3;
constexpr int max_block_depth = 2;
constexpr int max_array_size = 8;
constexpr int max_template_size = 5;
constexpr int max_user_variables = 6;
constexpr int max_subroutines = 3;

const std::vector<std::string> binary_operators = { "+",  "-",  "*", "/", "%",
                                                    "<<", ">>", "&", "|", "^" };
const std::vector<std::string> comparison_operators = { "==", "!=", "<", "<=", ">", ">=" };
const std::vector<std::string> compound_operators = { "+=",  "-=",  "*=", "/=", "%=",
                                                      "<<=", ">>=", "|=", "^=", "&=" };

// Binding levels of the binary operators (language.md §4.1), higher binds
// tighter; all are left-associative.
int binding_of(const std::string &op)
{
    if (op == "*" || op == "/" || op == "%")
        return 7;
    if (op == "+" || op == "-")
        return 6;
    if (op == "<<" || op == ">>")
        return 5;
    if (op == "&")
        return 4;
    if (op == "^")
        return 3;
    return 2; // "|"
}

// Tokens that may be packed against their neighbours without changing the
// token stream: they never combine with an adjacent character.
bool packable(const std::string &token)
{
    return token == "(" || token == ")" || token == "[" || token == "]" || token == "," ||
           token == ":";
}

// What a mutation may insert: tokens of every kind, valid or not.
const std::vector<std::string> mutation_vocabulary = {
    "=",      "+",    "-",       "*",     "/",         "%",      "(",      ")",         "[",
    "]",      ",",    ":",       "==",    "<",         ">=",     "!=",     "++",        "--",
    "+=",     "<<=",  "and",     "or",    "not",       "abs",    "if",     "then",      "else",
    "elseif", "end",  "when",    "do",    "while",     "for",    "in",     "step",      "emit",
    "_emit",  "call", "callsub", "sub",   "onevent",   "return", "var",    "const",     "0",
    "1",      "-1",   "32767",   "32768", "65536",     "0x8000", "0xFFFF", "0x1g",      "0b102",
    "007",    "1.5",  "12ab",    "0X10",  "x_unknown", "v0",     "K0",     "math.fill", "!",
    "@",      ";",    "{",       ".a",    "$",         "#*",     "é",      "timer"
};

int32_t wrap32(int64_t value)
{
    return int32_t(uint32_t(uint64_t(value)));
}

// The compiler's constant folding (language.md §9 rule 1): 32-bit C
// arithmetic with x86 shifts. Empty when folding would be an error.
std::optional<int32_t> fold(const std::string &op, int32_t a, int32_t b)
{
    if (op == "+")
        return wrap32(int64_t(a) + b);
    if (op == "-")
        return wrap32(int64_t(a) - b);
    if (op == "*")
        return wrap32(int64_t(a) * b);
    if (op == "/" || op == "%") {
        if (b == 0 || (a == INT32_MIN && b == -1))
            return std::nullopt;
        return op == "/" ? a / b : a % b;
    }
    if (op == "<<")
        return int32_t(uint32_t(a) << (uint32_t(b) & 31));
    if (op == ">>")
        return int32_t(a >> (uint32_t(b) & 31));
    if (op == "&")
        return a & b;
    if (op == "|")
        return a | b;
    return a ^ b; // "^"
}

} // namespace

ProgramGenerator::ProgramGenerator(uint32_t seed,
                                   const aseba::TargetDescription &target,
                                   const aseba::CommonDefinitions &definitions)
  : random_(seed)
  , target_(target)
  , definitions_(definitions)
{
}

// --- randomness --------------------------------------------------------------

unsigned ProgramGenerator::below(unsigned bound)
{
    return bound == 0 ? 0 : unsigned(random_() % bound);
}

bool ProgramGenerator::chance(unsigned percent)
{
    return below(100) < percent;
}

int ProgramGenerator::between(int low, int high)
{
    return low + int(below(unsigned(high - low + 1)));
}

// --- program structure ---------------------------------------------------------

GeneratedProgram ProgramGenerator::valid_program()
{
    generate_program();
    return { render(), "" };
}

GeneratedProgram ProgramGenerator::mutated_program()
{
    generate_program();
    const std::string mutation = mutate();
    return { render(), mutation };
}

void ProgramGenerator::reset()
{
    variables_.clear();
    for (const aseba::NamedVariable &variable : target_.named_variables)
        variables_.push_back({ variable.name, variable.size });
    constants_.clear();
    for (const aseba::Constant &constant : definitions_.constants)
        constants_.push_back({ constant.name, constant.value });
    global_events_.clear();
    for (const aseba::GlobalEvent &event : definitions_.events)
        global_events_.push_back({ event.name, event.size });
    subroutines_.clear();
    lines_.clear();
    indent_ = 0;
    name_counter_ = 0;
    spaced_ = chance(70);
    newline_ = chance(85) ? "\n" : "\r\n";
    indent_text_ = chance(50) ? "\t" : "  ";
}

void ProgramGenerator::generate_program()
{
    reset();
    for (int i = int(below(3)); i > 0; --i)
        constant_definition();
    for (int i = 1 + int(below(max_user_variables)); i > 0; --i)
        variable_definition();

    const int subroutine_count = int(below(max_subroutines + 1));
    for (int i = 0; i < subroutine_count; ++i)
        subroutines_.push_back("sub" + std::to_string(i) + (chance(20) ? ".part" : ""));

    // Init code: every subroutine may be called from events and init.
    block(0, subroutine_count, int(below(3)));

    // Handlers of some events, and the subroutines in their order, mixed.
    std::vector<std::string> events;
    for (const aseba::LocalEvent &event : target_.local_events)
        events.push_back(event.name);
    for (const NamedValue &event : global_events_)
        events.push_back(event.name);
    std::shuffle(events.begin(), events.end(), random_);
    events.resize(below(unsigned(events.size()) + 1));
    int next_subroutine = 0;
    std::size_t next_event = 0;
    while (next_subroutine < subroutine_count || next_event < events.size()) {
        const bool subroutine =
          next_event == events.size() || (next_subroutine < subroutine_count && chance(40));
        if (subroutine) {
            emit_line({ "sub", subroutines_[next_subroutine] });
            // A subroutine calls only earlier ones: no recursion (§11.3).
            block(0, next_subroutine, int(below(3)));
            ++next_subroutine;
        } else {
            emit_line({ "onevent", events[next_event++] });
            block(0, subroutine_count, int(below(4)));
        }
    }
}

void ProgramGenerator::constant_definition()
{
    const std::string name = "K" + std::to_string(name_counter_++);
    for (;;) {
        const Expression value = constant_expression(2);
        if (value.value && *value.value >= INT16_MIN && *value.value <= INT16_MAX) {
            Tokens line = { "const", name, "=" };
            line.insert(line.end(), value.tokens.begin(), value.tokens.end());
            emit_line(line);
            constants_.push_back({ name, *value.value });
            return;
        }
    }
}

void ProgramGenerator::variable_definition()
{
    const int number = name_counter_++;
    std::string name;
    switch (below(8)) {
    case 0: name = "_v" + std::to_string(number); break;
    case 1: name = "v" + std::to_string(number) + ".x"; break;
    case 2: name = "vé" + std::to_string(number); break;
    default: name = "v" + std::to_string(number); break;
    }
    const int size = chance(45) ? 1 : between(2, max_array_size);
    Tokens line = { "var", name };

    // The size: omitted for scalars, else a literal or a constant expression.
    const bool inferred = size > 1 && chance(15);
    if (inferred) {
        line.insert(line.end(), { "[", "]" });
    } else if (size > 1 || chance(10)) {
        line.push_back("[");
        bool written = false;
        for (const NamedValue &constant : constants_) {
            if (constant.value >= 1 && constant.value <= size && chance(40)) {
                line.push_back(constant.name);
                if (constant.value < size)
                    line.insert(line.end(), { "+", std::to_string(size - constant.value) });
                written = true;
                break;
            }
        }
        if (!written)
            line.push_back(std::to_string(size));
        line.push_back("]");
    }

    // The initializer, which may use the variables declared before.
    if (inferred || chance(50)) {
        line.push_back("=");
        if (size > 1 && !inferred && chance(25)) {
            // Legacy list: a plain first item, then any items (§4 legacy-list).
            const int first = between(-50, 50);
            if (first < 0)
                line.insert(line.end(), { "-", std::to_string(-first) });
            else
                line.push_back(std::to_string(first));
            for (int i = 1; i < size; ++i) {
                line.push_back(",");
                const Tokens item = list_item(expression(1, 1));
                line.insert(line.end(), item.begin(), item.end());
            }
        } else {
            const Expression value = expression(size, 2);
            line.insert(line.end(), value.tokens.begin(), value.tokens.end());
        }
    }
    emit_line(line);
    variables_.push_back({ name, size });
}

void ProgramGenerator::block(int depth, int subroutine, int count)
{
    ++indent_;
    for (int i = 0; i < count; ++i)
        statement(depth, subroutine);
    --indent_;
}

void ProgramGenerator::emit_line(Tokens tokens)
{
    Line line;
    line.indent = indent_;
    line.tokens = std::move(tokens);
    // Comments of every form (§2.1); tabs in comments shift columns (§11.1).
    if (chance(10)) {
        const std::string number = std::to_string(below(100));
        switch (below(5)) {
        case 0: line.comment = "#* note " + number + " *#"; break;
        case 1: line.comment = "#*\tspans" + newline_ + "two lines *#"; break;
        case 2: line.comment = "#**#"; break;
        case 3: line.comment = "#\tnote " + number; break;
        default: line.comment = "# note " + number; break;
        }
    }
    lines_.push_back(std::move(line));
}

// `subroutine`: how many subroutines (the first ones) this code may call.
void ProgramGenerator::statement(int depth, int subroutine)
{
    const bool nested = depth < max_block_depth;
    switch (below(nested ? 16 : 10)) {
    case 0:
    case 1:
    case 2: assignment(); break;
    case 3: compound_assignment(); break;
    case 4: increment(); break;
    case 5: emit_statement(); break;
    case 6:
    case 7: call_statement(); break;
    case 8:
        if (subroutine > 0)
            emit_line({ "callsub", subroutines_[below(unsigned(subroutine))] });
        else
            assignment();
        break;
    case 9:
        if (chance(30))
            emit_line({ "return" });
        else
            assignment();
        break;
    case 10:
    case 11: if_statement(depth, subroutine); break;
    case 12: when_statement(depth, subroutine); break;
    case 13: while_statement(depth, subroutine); break;
    default: for_statement(depth, subroutine); break;
    }
}

void ProgramGenerator::assignment()
{
    const int size = chance(65) ? 1 : between(2, max_variable_size());
    const Expression target = memory_reference(size, 2);
    const Expression value = expression(target.size, max_expression_depth);
    Tokens line = target.tokens;
    line.push_back("=");
    line.insert(line.end(), value.tokens.begin(), value.tokens.end());
    emit_line(line);
}

void ProgramGenerator::compound_assignment()
{
    const int size = chance(70) ? 1 : between(2, max_variable_size());
    const Expression target = memory_reference(size, 2);
    const std::string op = pick(compound_operators);
    const bool divides = op == "/=" || op == "%=";
    Expression value =
      divides && target.size > 1 ? memory_reference(target.size, 2) : expression(target.size, 2);
    if (divides && value.value && *value.value == 0)
        value = Expression{ { "3" }, 1, 3 };
    Tokens line = target.tokens;
    line.push_back(op);
    line.insert(line.end(), value.tokens.begin(), value.tokens.end());
    emit_line(line);
}

void ProgramGenerator::increment()
{
    const int size = chance(70) ? 1 : between(2, max_variable_size());
    Tokens line = memory_reference(size, 2).tokens;
    line.push_back(chance(50) ? "++" : "--");
    emit_line(line);
}

void ProgramGenerator::if_statement(int depth, int subroutine)
{
    Tokens head = { "if" };
    const Tokens first = condition(2);
    head.insert(head.end(), first.begin(), first.end());
    head.push_back("then");
    emit_line(head);
    block(depth + 1, subroutine, int(below(3)));
    for (int i = int(below(3)); i > 0 && chance(60); --i) {
        Tokens elseif = { "elseif" };
        const Tokens other = condition(2);
        elseif.insert(elseif.end(), other.begin(), other.end());
        elseif.push_back("then");
        emit_line(elseif);
        block(depth + 1, subroutine, int(below(3)));
    }
    if (chance(50)) {
        emit_line({ "else" });
        block(depth + 1, subroutine, int(below(3)));
    }
    emit_line({ "end" });
}

void ProgramGenerator::when_statement(int depth, int subroutine)
{
    Tokens head = { "when" };
    const Tokens test = condition(2);
    head.insert(head.end(), test.begin(), test.end());
    head.push_back("do");
    emit_line(head);
    block(depth + 1, subroutine, int(below(3)));
    emit_line({ "end" });
}

void ProgramGenerator::while_statement(int depth, int subroutine)
{
    // The left side reads memory, so the condition never folds to a
    // constant ("Infinite loops not allowed").
    Tokens head = { "while" };
    const Expression left = memory_reference(1, 1);
    const Expression right = expression(1, 2);
    head.insert(head.end(), left.tokens.begin(), left.tokens.end());
    head.push_back(pick(comparison_operators));
    head.insert(head.end(), right.tokens.begin(), right.tokens.end());
    head.push_back("do");
    emit_line(head);
    block(depth + 1, subroutine, 1 + int(below(3)));
    emit_line({ "end" });
}

void ProgramGenerator::for_statement(int depth, int subroutine)
{
    // Bounds and step are literals (possibly negative) or constant names;
    // their order must match the step's sign (language.md §8.5).
    int step = 1;
    bool step_written = chance(50);
    std::string step_name;
    if (step_written) {
        step = pick(std::vector<int>{ 1, 2, 3, 5, -1, -2, -3 });
        for (const NamedValue &constant : constants_)
            if (constant.value > 0 && constant.value < 10 && chance(30)) {
                step = constant.value;
                step_name = constant.name;
            }
    }
    int start = between(-20, 20);
    int end = between(-20, 20);
    if (chance(5)) {
        start = step > 0 ? 32700 : -32700;
        end = step > 0 ? 32766 : -32767;
    }
    if ((step > 0) == (start > end))
        std::swap(start, end);
    auto bound = [&](int value) {
        for (const NamedValue &constant : constants_)
            if (constant.value == value && chance(70))
                return Tokens{ constant.name };
        if (value < 0)
            return Tokens{ "-", std::to_string(-value) };
        return Tokens{ std::to_string(value) };
    };
    Tokens head = { "for" };
    const Tokens variable = loop_variable(1);
    head.insert(head.end(), variable.begin(), variable.end());
    head.push_back("in");
    const Tokens from = bound(start), to = bound(end);
    head.insert(head.end(), from.begin(), from.end());
    head.push_back(":");
    head.insert(head.end(), to.begin(), to.end());
    if (step_written) {
        head.push_back("step");
        if (!step_name.empty())
            head.push_back(step_name);
        else if (step < 0)
            head.insert(head.end(), { "-", std::to_string(-step) });
        else
            head.push_back(std::to_string(step));
    }
    head.push_back("do");
    emit_line(head);
    block(depth + 1, subroutine, int(below(3)));
    emit_line({ "end" });
}

void ProgramGenerator::emit_statement()
{
    if (global_events_.empty()) {
        assignment();
        return;
    }
    const NamedValue &event = pick(global_events_);
    const bool hidden = chance(25);
    Tokens line = { hidden ? "_emit" : "emit", event.name };
    if (event.value > 0) {
        // _emit accepts an argument up to the event's size (§8.6).
        const int size = hidden ? between(1, event.value) : event.value;
        const Expression argument = chance(50) ? memory_reference(size, 1) : expression(size, 2);
        line.insert(line.end(), argument.tokens.begin(), argument.tokens.end());
    }
    emit_line(line);
}

void ProgramGenerator::call_statement()
{
    if (target_.native_functions.empty()) {
        assignment();
        return;
    }
    const aseba::NativeFunction &native = pick(target_.native_functions);
    // One size per template id, shared by its parameters (§8.7).
    std::vector<int> template_sizes(8);
    for (int &size : template_sizes)
        size = between(1, max_template_size);
    Tokens line = { "call", native.name, "(" };
    bool first = true;
    for (const aseba::NativeParameter &parameter : native.parameters) {
        int size = parameter.size;
        if (size < 0)
            size = template_sizes[std::size_t(-size) % template_sizes.size()];
        else if (size == 0)
            size = between(1, max_template_size);
        if (!first)
            line.push_back(",");
        first = false;
        const Expression argument = chance(60) ? memory_reference(size, 1) : expression(size, 2);
        line.insert(line.end(), argument.tokens.begin(), argument.tokens.end());
    }
    line.push_back(")");
    emit_line(line);
}

// --- expressions -----------------------------------------------------------------

ProgramGenerator::Expression ProgramGenerator::expression(int size, int depth)
{
    if (depth <= 0 || chance(40))
        return size == 1 ? scalar_leaf(depth) : vector_leaf(size, depth);
    const unsigned choice = below(100);
    if (choice < 55) {
        const std::string op = pick(binary_operators);
        const Expression left = expression(size, depth - 1);
        // Values of vector elements are not tracked: a vector divisor reads
        // memory, so that no element folds to a constant 0.
        const bool vector_divisor = size > 1 && (op == "/" || op == "%");
        const Expression right =
          vector_divisor ? memory_reference(size, depth - 1) : expression(size, depth - 1);
        return binary(left, op, right);
    }
    if (choice < 72) {
        const std::string op = pick(std::vector<std::string>{ "-", "~", "abs" });
        // Same for abs: no vector element may fold to -32768.
        if (op == "abs" && size > 1)
            return unary(op, memory_reference(size, depth - 1));
        return unary(op, expression(size, depth - 1));
    }
    if (choice < 85)
        return tuple(size, depth);
    Expression inner = expression(size, depth - 1);
    inner.tokens.insert(inner.tokens.begin(), "(");
    inner.tokens.push_back(")");
    inner.binding = primary;
    return inner;
}

ProgramGenerator::Expression ProgramGenerator::binary(const Expression &left,
                                                      const std::string &op,
                                                      Expression right)
{
    // A constant divisor must not fold to 0 ("Division by zero") nor make
    // the folding itself overflow.
    if ((op == "/" || op == "%") && right.value &&
        (*right.value == 0 || (*right.value == -1 && left.value && *left.value == INT32_MIN)))
        right = Expression{ { "7" }, right.size, 7 };

    // Operands get parentheses where precedence and left associativity
    // would otherwise parse another tree than the one whose value is
    // tracked (`a - (b - c)`, `(a + b) * c`), and sometimes where not needed.
    const int level = binding_of(op);
    auto operand = [&](const Expression &side, bool is_right) {
        Tokens tokens = side.tokens;
        const bool needed = is_right ? side.binding <= level : side.binding < level;
        if (needed || chance(10)) {
            tokens.insert(tokens.begin(), "(");
            tokens.push_back(")");
        }
        return tokens;
    };
    Expression result;
    result.size = left.size;
    result.binding = level;
    result.tokens = operand(left, false);
    result.tokens.push_back(op);
    const Tokens right_tokens = operand(right, true);
    result.tokens.insert(result.tokens.end(), right_tokens.begin(), right_tokens.end());
    if (left.value && right.value)
        result.value = fold(op, *left.value, *right.value);
    else if ((op == "*" || op == "&") &&
             ((left.value && *left.value == 0) || (right.value && *right.value == 0)))
        result.value = 0; // absorbing element (§9 rule 4)
    else if (op == "|" &&
             ((left.value && *left.value == -1) || (right.value && *right.value == -1)))
        result.value = -1;
    if (result.size != 1)
        result.value.reset();
    return result;
}

ProgramGenerator::Expression ProgramGenerator::unary(const std::string &op,
                                                     const Expression &operand)
{
    Expression inner = operand;
    // abs of a constant -32768 is a compile error (§9 rule 2).
    if (op == "abs" && inner.value && *inner.value == INT16_MIN)
        inner = Expression{ { "5" }, 1, 5 };
    // "-" then a literal is folded into the literal, and -0x8000 is out of
    // range (§2.4): keep such a literal apart with parentheses.
    const bool hex_minimum = inner.tokens.size() == 1 && inner.value && *inner.value == INT16_MIN;
    if (!inner.atomic() || (op == "-" && hex_minimum)) {
        inner.tokens.insert(inner.tokens.begin(), "(");
        inner.tokens.push_back(")");
    }
    Expression result;
    result.size = inner.size;
    result.tokens = { op };
    result.tokens.insert(result.tokens.end(), inner.tokens.begin(), inner.tokens.end());
    if (inner.value && inner.size == 1) {
        const int32_t value = *inner.value;
        if (op == "-")
            result.value = wrap32(-int64_t(value));
        else if (op == "~")
            result.value = ~value;
        else
            result.value = value < 0 ? wrap32(-int64_t(value)) : value;
    }
    return result;
}

// Inside a tuple or a legacy list an item that starts with "[" is read as a
// tuple only (§4 list-item), so `[[1] * 3, 2]` is a syntax error: such an
// item gets parentheses.
ProgramGenerator::Tokens ProgramGenerator::list_item(const Expression &item)
{
    Tokens tokens = item.tokens;
    if (!item.atomic() && tokens.front() == "[") {
        tokens.insert(tokens.begin(), "(");
        tokens.push_back(")");
    }
    return tokens;
}

ProgramGenerator::Expression ProgramGenerator::tuple(int size, int depth)
{
    Expression result;
    result.size = size;
    result.tokens = { "[" };
    int remaining = size;
    while (remaining > 0) {
        // Parts of size 1 only at the bottom, so that recursion ends.
        const int part = depth <= 0 || chance(60) ? 1 : between(1, remaining);
        const Expression item = expression(part, depth - 1);
        const Tokens item_tokens = list_item(item);
        if (remaining != size)
            result.tokens.push_back(",");
        result.tokens.insert(result.tokens.end(), item_tokens.begin(), item_tokens.end());
        if (size == 1)
            result.value = item.value; // [c] folds to c
        remaining -= part;
    }
    result.tokens.push_back("]");
    return result;
}

ProgramGenerator::Expression ProgramGenerator::scalar_leaf(int depth)
{
    const unsigned choice = below(100);
    if (choice < 30)
        return literal();
    if (choice < 40 && !constants_.empty()) {
        const NamedValue &constant = pick(constants_);
        return Expression{ { constant.name }, 1, constant.value };
    }
    return memory_reference(1, depth);
}

ProgramGenerator::Expression ProgramGenerator::vector_leaf(int size, int depth)
{
    if (chance(65))
        return memory_reference(size, depth);
    return tuple(size, depth);
}

std::string ProgramGenerator::literal_text(int value)
{
    if (value >= 0 && chance(15)) {
        static const char digits[] = "0123456789abcdef";
        std::string hex;
        for (int v = value; v > 0; v /= 16)
            hex.insert(hex.begin(), digits[v % 16]);
        return "0x" + hex; // "0x" alone is 0 (§2.3)
    }
    if (value >= 0 && value < 64 && chance(10)) {
        std::string binary;
        for (int v = value; v > 0; v /= 2)
            binary.insert(binary.begin(), char('0' + v % 2));
        return "0b" + binary;
    }
    if (value > 0 && value < 10 && chance(5))
        return "00" + std::to_string(value);
    return std::to_string(value);
}

ProgramGenerator::Expression ProgramGenerator::literal()
{
    static const std::vector<int> edges = { 2047,   2048, -2047, -2048, 32767, -32768,
                                            -32767, 1000, -1,    4095,  4096 };
    const unsigned choice = below(100);
    int value = 0;
    if (choice < 70)
        value = between(0, 20);
    else if (choice < 85)
        value = pick(edges);
    else if (choice < 92)
        value = between(-300, 300);
    else {
        // Hexadecimal literals from 0x8000 are negative (§2.4).
        struct HexLiteral {
            const char *text;
            int16_t value;
        };
        static const std::vector<HexLiteral> hex_literals = {
            { "0x8000", INT16_MIN }, { "0xFFFF", -1 }, { "0x7fff", INT16_MAX }, { "0xC000", -16384 }
        };
        const HexLiteral &hex = pick(hex_literals);
        return Expression{ { hex.text }, 1, hex.value };
    }
    if (value < 0)
        return Expression{ { "-", std::to_string(-value) }, 1, value };
    return Expression{ { literal_text(value) }, 1, value };
}

ProgramGenerator::Expression ProgramGenerator::constant_expression(int depth)
{
    Expression left = constants_.empty() || chance(50)
                        ? Expression{ { std::to_string(between(0, 30)) }, 1, 0 }
                        : Expression{ { pick(constants_).name }, 1, 0 };
    if (left.tokens[0][0] >= '0' && left.tokens[0][0] <= '9')
        left.value = std::stoi(left.tokens[0]);
    else
        for (const NamedValue &constant : constants_)
            if (constant.name == left.tokens[0])
                left.value = constant.value;
    if (depth <= 0 || chance(40))
        return left;
    const std::string op = pick(std::vector<std::string>{ "+", "-", "*", "<<", "|" });
    return binary(left, op, constant_expression(depth - 1));
}

std::vector<const ProgramGenerator::Variable *> ProgramGenerator::variables_of_size(int size) const
{
    std::vector<const Variable *> found;
    for (const Variable &variable : variables_)
        if (variable.size == size)
            found.push_back(&variable);
    return found;
}

std::vector<const ProgramGenerator::Variable *> ProgramGenerator::arrays_of_at_least(int size) const
{
    std::vector<const Variable *> found;
    for (const Variable &variable : variables_)
        if (variable.size >= size)
            found.push_back(&variable);
    return found;
}

int ProgramGenerator::max_variable_size() const
{
    int largest = 1;
    for (const Variable &variable : variables_)
        largest = std::max(largest, std::min(variable.size, max_array_size));
    return largest;
}

ProgramGenerator::Expression ProgramGenerator::element(const Variable &array, int depth)
{
    Expression result;
    result.tokens = { array.name, "[" };
    const unsigned choice = below(100);
    if (choice < 45 || depth <= 0) {
        result.tokens.push_back(literal_text(between(0, array.size - 1)));
    } else if (choice < 55) {
        bool written = false;
        for (const NamedValue &constant : constants_)
            if (constant.value >= 0 && constant.value < array.size) {
                result.tokens.push_back(constant.name);
                written = true;
                break;
            }
        if (!written)
            result.tokens.push_back("0");
    } else {
        // A run-time index; one that folds must still be in bounds (§6).
        // A tuple index (even in parentheses) with a variable inside makes
        // the reference compiler abort (an upstream assertion): none here.
        const Expression index = expression(1, depth - 1);
        const auto tuple_start = std::find_if(
          index.tokens.begin(), index.tokens.end(), [](const std::string &t) { return t != "("; });
        if (index.value && (*index.value < 0 || *index.value >= array.size))
            result.tokens.push_back(std::to_string(array.size - 1));
        else if (index.atomic() && tuple_start != index.tokens.end() && *tuple_start == "[")
            result.tokens.push_back(literal_text(between(0, array.size - 1)));
        else
            result.tokens.insert(result.tokens.end(), index.tokens.begin(), index.tokens.end());
    }
    result.tokens.push_back("]");
    return result;
}

ProgramGenerator::Expression ProgramGenerator::memory_reference(int size, int depth)
{
    const std::vector<const Variable *> exact = variables_of_size(size);
    const std::vector<const Variable *> larger = arrays_of_at_least(size + (size == 1 ? 1 : 0));
    const unsigned choice = below(100);
    if (!exact.empty() && (choice < 50 || larger.empty()))
        return Expression{ { pick(exact)->name }, size, std::nullopt };
    if (!larger.empty()) {
        const Variable &array = *pick(larger);
        if (size == 1 && chance(80))
            return element(array, depth);
        const int start = between(0, array.size - size);
        return Expression{
            { array.name, "[", literal_text(start), ":", literal_text(start + size - 1), "]" },
            size,
            std::nullopt
        };
    }
    // No variable fits: a tuple of literals (only where an expression is
    // allowed; callers needing memory never ask for such sizes).
    return tuple(size, 0);
}

ProgramGenerator::Tokens ProgramGenerator::loop_variable(int depth)
{
    return memory_reference(1, depth).tokens;
}

ProgramGenerator::Tokens ProgramGenerator::comparison(int depth)
{
    Tokens tokens = expression(1, depth).tokens;
    tokens.push_back(pick(comparison_operators));
    const Tokens right = expression(1, depth).tokens;
    tokens.insert(tokens.end(), right.begin(), right.end());
    return tokens;
}

ProgramGenerator::Tokens ProgramGenerator::condition(int depth)
{
    const unsigned choice = below(100);
    if (depth <= 0 || choice < 45)
        return comparison(depth);
    if (choice < 80) {
        Tokens tokens = condition(depth - 1);
        tokens.push_back(chance(50) ? "and" : "or");
        const Tokens right = condition(depth - 1);
        tokens.insert(tokens.end(), right.begin(), right.end());
        return tokens;
    }
    if (choice < 90) {
        Tokens tokens = { "not" };
        const Tokens inner = comparison(depth - 1);
        tokens.insert(tokens.end(), inner.begin(), inner.end());
        return tokens;
    }
    Tokens tokens = chance(50) ? Tokens{ "not", "(" } : Tokens{ "(" };
    const Tokens inner = condition(depth - 1);
    tokens.insert(tokens.end(), inner.begin(), inner.end());
    tokens.push_back(")");
    return tokens;
}

// --- rendering and mutation ------------------------------------------------------

std::string ProgramGenerator::render_line(const Line &line) const
{
    std::string text;
    for (int i = 0; i < line.indent; ++i)
        text += indent_text_;
    for (std::size_t i = 0; i < line.tokens.size(); ++i) {
        if (i > 0 && (spaced_ || !(packable(line.tokens[i]) || packable(line.tokens[i - 1]))))
            text += " ";
        text += line.tokens[i];
    }
    if (!line.comment.empty())
        text += " " + line.comment;
    return text;
}

std::string ProgramGenerator::render() const
{
    std::string text;
    for (const Line &line : lines_)
        text += render_line(line) + newline_;
    return text;
}

std::string ProgramGenerator::mutate()
{
    if (lines_.empty())
        lines_.push_back({ 0, { "x_unknown", "=", "1" }, "" });
    Line &line = lines_[below(unsigned(lines_.size()))];
    const std::size_t position = below(unsigned(line.tokens.size()));
    const std::string token = pick(mutation_vocabulary);
    switch (below(13)) {
    case 10:
    case 11:
    case 0: line.tokens.erase(line.tokens.begin() + long(position)); return "deleted a token";
    case 1:
        line.tokens.insert(line.tokens.begin() + long(position), token);
        return "inserted " + token;
    case 2: line.tokens[position] = token; return "replaced a token by " + token;
    case 3:
        if (position + 1 < line.tokens.size())
            std::swap(line.tokens[position], line.tokens[position + 1]);
        return "swapped two tokens";
    case 4: {
        const Line copy = line;
        lines_.insert(lines_.begin() + long(&line - lines_.data()), copy);
        return "duplicated a line";
    }
    case 5: lines_.erase(lines_.begin() + long(&line - lines_.data())); return "deleted a line";
    case 6: {
        const std::size_t keep = &line - lines_.data();
        line.tokens.resize(position);
        lines_.resize(keep + 1);
        return "truncated the program";
    }
    case 7: {
        // A typo in a name, which the compilers may answer with a suggestion.
        std::string &word = line.tokens[position];
        const bool is_name = std::isalpha(static_cast<unsigned char>(word[0])) || word[0] == '_';
        if (is_name && word.size() > 2 && chance(50))
            word.pop_back();
        else if (is_name)
            word += "x";
        return "changed a name to " + word;
    }
    case 8: {
        // A declaration after code is an error (§3).
        const std::size_t index = &line - lines_.data();
        lines_.insert(lines_.begin() + long(index), Line{ 0, { "var", "late", "=", "1" }, "" });
        return "inserted a declaration";
    }
    default:
        line.tokens.insert(line.tokens.begin() + long(position), { "#*", "open", "comment" });
        return "opened a block comment";
    }
}

} // namespace compiler_tests
