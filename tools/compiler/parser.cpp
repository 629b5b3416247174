// The recursive-descent parser of language.md §3-§4. Besides building the
// tree it does what the reference does while parsing: declares constants and
// variables, resolves names, events and natives, and allocates the
// temporaries of `emit` and native-call arguments (§7).

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "compilation.hpp"
#include "diagnostics.hpp"
#include "lexer.hpp"
#include "vm_opcodes.h"

namespace aseba
{

namespace
{

constexpr int64_t INT16_MAX_VALUE = 32767;
constexpr int64_t INT16_MIN_VALUE = -32768;
constexpr unsigned MAX_NESTING = 300;            // blocks, parentheses and unary operators
constexpr unsigned MAX_EXPRESSION_HEIGHT = 1000; // keeps every later phase off deep recursion

const char *const OPERAND_LIST = "( (open parenthesis), [ (open bracket), - (minus), binary not, "
                                 "abs keyword, string, integer";

std::string range_message(int64_t value)
{
    return "Integer value " + std::to_string(value) + " out of [-32768;32767] range";
}

class Parser
{
  public:
    Parser(const std::vector<Token> &token_list, Compilation &state)
      : tokens(token_list)
      , compilation(state)
    {
    }

    NodePointer program()
    {
        auto block = make_node(NodeKind::Block, { 1, 1 });
        while (is(TokenType::CONST))
            constant_definition();
        while (is(TokenType::VAR)) {
            compilation.temporaries_used = 0;
            add(*block, variable_definition());
        }
        while (!is(TokenType::END_OF_STREAM)) {
            compilation.temporaries_used = 0;
            if (is(TokenType::VAR))
                add(*block, variable_definition()); // the 2007 paper's dialect
            else if (is(TokenType::ONEVENT) || is(TokenType::SUB))
                block->children.push_back(section_start());
            else
                add(*block, statement());
        }
        return block;
    }

  private:
    const std::vector<Token> &tokens;
    Compilation &compilation;
    size_t current = 0;
    unsigned nesting = 0;

    // Counts one level of recursion for as long as it lives.
    class NestingGuard
    {
      public:
        NestingGuard(unsigned &level, SourcePosition where)
          : counter(level)
        {
            if (++counter > MAX_NESTING)
                fail(where,
                     "This program nests too deeply (more than " + std::to_string(MAX_NESTING) +
                       " levels)");
        }
        ~NestingGuard()
        {
            --counter;
        }
        NestingGuard(const NestingGuard &) = delete;
        NestingGuard &operator=(const NestingGuard &) = delete;

      private:
        unsigned &counter;
    };

    static void add(Node &block, NodePointer statement)
    {
        if (statement)
            block.children.push_back(std::move(statement));
    }

    const Token &token() const
    {
        return tokens[current];
    }
    bool is(TokenType type) const
    {
        return token().type == type;
    }
    SourcePosition position() const
    {
        return token().position;
    }
    const Token &next()
    {
        const Token &taken = tokens[current];
        if (current + 1 < tokens.size())
            ++current;
        return taken;
    }
    [[noreturn]] void fail_expecting(TokenType expected) const
    {
        fail(position(),
             std::string("Expecting ") + token_type_name(expected) + ", found " +
               token_type_name(token().type) + " instead");
    }
    const Token &expect(TokenType type)
    {
        if (!is(type))
            fail_expecting(type);
        return next();
    }

    // --- definitions --------------------------------------------------------

    // The current token as the reference shows it in two messages (§11.2):
    // line, 0-based column, name and, for names and numbers, the value.
    std::string token_dump() const
    {
        const Token &shown = token();
        char place[32];
        std::snprintf(place,
                      sizeof place,
                      "%4u:%-4u",
                      shown.position.line,
                      shown.position.column - 1); // column 0 shows as 2^32 - 1, as upstream
        std::string dump = std::string(place) + " " + token_type_name(shown.type);
        if (shown.type == TokenType::IDENTIFIER)
            dump += " : " + shown.text;
        else if (shown.type == TokenType::INTEGER)
            dump += " : " + std::to_string(shown.value);
        return dump;
    }

    [[noreturn]] void fail_expecting_assignment() const
    {
        fail(position(), "Expecting assignment, found " + token_dump() + " instead");
    }

    // The name of a `var` or `const` definition.
    const Token &defined_name()
    {
        if (!is(TokenType::IDENTIFIER))
            fail(position(), "Expecting identifier, found " + token_dump());
        return next();
    }

    void constant_definition()
    {
        next();
        const Token &name = defined_name();
        if (compilation.find_constant(name.text))
            fail(name.position, "Constant " + name.text + " is already defined");
        if (!is(TokenType::ASSIGN))
            fail_expecting_assignment();
        next();
        NodePointer expression = binary_or();
        std::optional<int64_t> value = evaluate_constant(*expression, true);
        if (!value) {
            check_constant_indexes(*expression); // the reference's order
            fail(name.position, "Not a valid constant expression");
        }
        if (*value < INT16_MIN_VALUE || *value > INT16_MAX_VALUE)
            fail(name.position,
                 "Constant " + name.text + " has value " + std::to_string(*value) +
                   ", which is out of [-32768;32767] range");
        compilation.constants[name.text] = *value;
    }

    NodePointer variable_definition()
    {
        next();
        const Token &name = defined_name();
        if (compilation.find_variable(name.text))
            fail(name.position, "Variable " + name.text + " is already defined");
        if (compilation.find_constant(name.text))
            fail(name.position, "Variable " + name.text + " has the same name as a constant");
        int64_t declared_size = 1;
        bool size_known = true;
        if (is(TokenType::BRACKET_OPEN)) {
            SourcePosition bracket = next().position;
            size_known = false;
            if (!is(TokenType::BRACKET_CLOSE)) {
                NodePointer size_expression = binary_or();
                std::optional<int64_t> value = evaluate_constant(*size_expression, true);
                if (!value) {
                    check_constant_indexes(*size_expression); // the reference's order
                    fail(bracket, "Not a valid constant expression");
                }
                if (*value < 0)
                    fail(bracket,
                         "Array size: result is negative (" + std::to_string(*value) + ")");
                if (*value == 0)
                    fail(bracket, "Array size: result is null");
                declared_size = *value;
                size_known = true;
            }
            expect(TokenType::BRACKET_CLOSE);
        }
        NodePointer initializer;
        SourcePosition assign_position;
        if (is(TokenType::ASSIGN)) {
            assign_position = next().position;
            initializer = initial_value();
        }
        if (!size_known) {
            if (!initializer)
                fail(name.position, "Array " + name.text + " has undefined size");
            declared_size = vector_size(*initializer);
        }
        if (compilation.next_free_address + declared_size > compilation.target.variables_size)
            fail(name.position, "No more free variable space");
        auto size = static_cast<unsigned>(declared_size);
        compilation.variables.push_back({ name.text,
                                          static_cast<uint16_t>(compilation.next_free_address),
                                          static_cast<uint16_t>(size) });
        unsigned address = compilation.next_free_address;
        compilation.next_free_address += size;
        if (!initializer)
            return nullptr;
        auto target = make_node(NodeKind::Memory, name.position);
        target->name = name.text;
        target->address = address;
        target->variable_size = size;
        auto assignment = make_node(NodeKind::Assignment, assign_position);
        assignment->children.push_back(std::move(target));
        assignment->children.push_back(std::move(initializer));
        return assignment;
    }

    // `= e` or the legacy list `= a, b, c`.
    NodePointer initial_value()
    {
        bool legacy = tokens[std::min(current + 1, tokens.size() - 1)].type == TokenType::COMMA ||
                      (is(TokenType::MINUS) &&
                       tokens[std::min(current + 2, tokens.size() - 1)].type == TokenType::COMMA);
        if (!legacy)
            return binary_or();
        auto tuple = make_node(NodeKind::Tuple, position());
        tuple->children.push_back(list_item());
        while (is(TokenType::COMMA)) {
            next();
            tuple->children.push_back(list_item());
        }
        return tuple;
    }

    // An `onevent` or `sub` marker.
    NodePointer section_start()
    {
        return is(TokenType::ONEVENT) ? event_start() : subroutine_start();
    }

    NodePointer event_start()
    {
        next();
        const Token &name = expect(TokenType::IDENTIFIER);
        std::optional<unsigned> id = compilation.find_global_event(name.text);
        if (!id)
            id = compilation.find_local_event(name.text);
        if (!id) {
            std::vector<std::string> names;
            for (const auto &event : compilation.definitions.events)
                names.push_back(event.name);
            for (const auto &event : compilation.target.local_events)
                names.push_back(event.name);
            fail(name.position,
                 with_suggestion(name.text + " is not a known event", name.text, names));
        }
        auto &implemented = compilation.implemented_events;
        if (std::find(implemented.begin(), implemented.end(), *id) != implemented.end())
            fail(name.position, "Event " + name.text + " is already implemented");
        implemented.push_back(*id);
        auto marker = make_node(NodeKind::EventStart, name.position);
        marker->event_id = *id;
        return marker;
    }

    NodePointer subroutine_start()
    {
        next();
        const Token &name = expect(TokenType::IDENTIFIER);
        if (compilation.find_subroutine(name.text))
            fail(name.position, "Subroutine " + name.text + " is already defined");
        compilation.subroutines.push_back(name.text);
        auto marker = make_node(NodeKind::SubStart, name.position);
        marker->name = name.text;
        return marker;
    }

    // --- statements ---------------------------------------------------------

    NodePointer statement()
    {
        NestingGuard guard(nesting, position());
        switch (token().type) {
        case TokenType::IF: return if_statement();
        case TokenType::WHEN: return when_statement();
        case TokenType::WHILE: return while_statement();
        case TokenType::FOR: return for_statement();
        case TokenType::EMIT:
        case TokenType::HIDDEN_EMIT: return emit_statement();
        case TokenType::CALL: return call_statement();
        case TokenType::CALLSUB: {
            SourcePosition where = next().position;
            const Token &name = expect(TokenType::IDENTIFIER);
            auto call = make_node(NodeKind::CallSub, where);
            call->name = name.text;
            return call;
        }
        case TokenType::RETURN: return make_node(NodeKind::Return, next().position);
        default: return assignment();
        }
    }

    // Statements until one of the `enders` (not consumed).
    NodePointer block(std::initializer_list<TokenType> enders)
    {
        auto result = make_node(NodeKind::Block, position());
        while (std::find(enders.begin(), enders.end(), token().type) == enders.end())
            add(*result, statement());
        return result;
    }

    NodePointer if_statement()
    {
        auto node = make_node(NodeKind::If, next().position);
        node->children.push_back(or_expression());
        expect(TokenType::THEN);
        node->children.push_back(block({ TokenType::END, TokenType::ELSE, TokenType::ELSEIF }));
        node->has_else = is(TokenType::ELSEIF) || is(TokenType::ELSE);
        node->else_is_elseif = is(TokenType::ELSEIF);
        if (is(TokenType::ELSEIF)) {
            auto else_block = make_node(NodeKind::Block, position());
            else_block->children.push_back(if_statement()); // shares the final `end`
            // The reference leaves the line of an `if` continued by `elseif`
            // unset: code after it is attributed to the first line.
            node->end_line = 1;
            node->children.push_back(std::move(else_block));
            return node;
        }
        if (is(TokenType::ELSE)) {
            next();
            node->children.push_back(block({ TokenType::END }));
        } else {
            node->children.push_back(make_node(NodeKind::Block, position()));
        }
        node->end_line = expect(TokenType::END).position.line;
        return node;
    }

    NodePointer when_statement()
    {
        auto node = make_node(NodeKind::If, next().position);
        node->is_when = true;
        node->children.push_back(or_expression());
        expect(TokenType::DO);
        node->children.push_back(block({ TokenType::END, TokenType::ELSE, TokenType::ELSEIF }));
        node->children.push_back(make_node(NodeKind::Block, position()));
        node->end_line = expect(TokenType::END).position.line;
        return node;
    }

    NodePointer while_statement()
    {
        auto node = make_node(NodeKind::While, next().position);
        node->children.push_back(or_expression());
        expect(TokenType::DO);
        node->children.push_back(block({ TokenType::END }));
        expect(TokenType::END);
        return node;
    }

    // A `for` bound or step: [-] integer, or a constant's name.
    std::pair<int64_t, SourcePosition> integer_constant()
    {
        SourcePosition where = position();
        if (is(TokenType::MINUS)) {
            next();
            const Token &literal = expect(TokenType::INTEGER);
            int64_t value = -static_cast<int64_t>(literal.value);
            if (value < INT16_MIN_VALUE || value > INT16_MAX_VALUE)
                fail(literal.position, range_message(std::abs(value))); // the literal as written
            return { value, literal.position };
        }
        if (is(TokenType::INTEGER)) {
            const Token &literal = next();
            if (literal.value > INT16_MAX_VALUE)
                fail(literal.position, range_message(literal.value));
            return { literal.value, where };
        }
        const Token &name = expect(TokenType::IDENTIFIER);
        std::optional<int64_t> value = compilation.find_constant(name.text);
        if (!value) {
            std::vector<std::string> names;
            for (const auto &constant : compilation.constants)
                names.push_back(constant.first);
            fail(name.position,
                 with_suggestion("Constant " + name.text + " not defined", name.text, names));
        }
        return { *value, where };
    }

    NodePointer for_statement()
    {
        SourcePosition for_position = next().position;
        if (!is(TokenType::IDENTIFIER))
            fail_expecting(TokenType::IDENTIFIER);
        NodePointer variable = variable_reference();
        expect(TokenType::IN);
        auto [start, start_position] = integer_constant();
        expect(TokenType::COLON);
        auto [end, end_position] = integer_constant();
        int64_t step = 1;
        if (is(TokenType::STEP)) {
            next();
            auto [step_value, step_position] = integer_constant();
            step = step_value;
            if (step == 0)
                fail(step_position, "Null steps are not allowed in for loops");
        }
        if (step > 0) {
            if (start > end)
                fail(start_position,
                     "Start index must be lower than end index in increasing loops");
            if (end == INT16_MAX_VALUE)
                fail(end_position, "End index cannot be 32767 in increasing loops");
        } else {
            if (start < end)
                fail(start_position,
                     "Start index must be higher than end index in decreasing loops");
            if (end == INT16_MIN_VALUE)
                fail(end_position, "End index cannot be -32768 in decreasing loops");
        }
        expect(TokenType::DO);
        NodePointer body = block({ TokenType::END });
        expect(TokenType::END);

        auto result = make_node(NodeKind::Block, for_position);
        auto initial = make_node(NodeKind::Assignment, start_position);
        initial->children.push_back(clone(*variable));
        initial->children.push_back(immediate(start, start_position));
        result->children.push_back(std::move(initial));
        if (start == end) {
            result->children.push_back(std::move(body));
            return result;
        }
        auto loop = make_node(NodeKind::While, for_position);
        auto condition = make_node(NodeKind::Binary, for_position);
        condition->operation =
          start < end ? VM_BINARY_SMALLER_EQUAL_THAN : VM_BINARY_BIGGER_EQUAL_THAN;
        condition->children.push_back(clone(*variable));
        condition->children.push_back(immediate(end, for_position));
        loop->children.push_back(std::move(condition));
        auto increment = make_node(NodeKind::Assignment, for_position);
        auto sum = make_node(NodeKind::Binary, for_position);
        sum->operation = VM_BINARY_ADD;
        sum->children.push_back(clone(*variable));
        sum->children.push_back(immediate(step, for_position));
        increment->children.push_back(std::move(variable));
        increment->children.push_back(std::move(sum));
        body->children.push_back(std::move(increment));
        loop->children.push_back(std::move(body));
        result->children.push_back(std::move(loop));
        return result;
    }

    static NodePointer immediate(int64_t value, SourcePosition where)
    {
        auto node = make_node(NodeKind::Immediate, where);
        node->value = value;
        return node;
    }

    // A Memory node for `size` words of temporary at `address`.
    static NodePointer temporary(unsigned address, unsigned size, SourcePosition where)
    {
        auto node = make_node(NodeKind::Memory, where);
        node->name = TEMPORARY_NAME;
        node->address = address;
        node->variable_size = size;
        return node;
    }

    // An assignment of `value` to a fresh temporary of its size, allocated
    // now; `address` receives where it lives.
    NodePointer fill_temporary(NodePointer value, SourcePosition where, unsigned &address)
    {
        unsigned size = vector_size(*value);
        address = compilation.allocate_temporary(size, where);
        auto assignment = make_node(NodeKind::Assignment, where);
        assignment->children.push_back(temporary(address, size, where));
        assignment->children.push_back(std::move(value));
        return assignment;
    }

    // Checks every constant index and slice of `expression`, in tree order.
    static void check_constant_indexes(const Node &expression)
    {
        if (expression.kind == NodeKind::Memory)
            check_constant_index(expression);
        for (const auto &child : expression.children)
            check_constant_indexes(*child);
    }

    static bool is_direct_memory(const Node &node)
    {
        return node.kind == NodeKind::Memory && node.index_form != IndexForm::Expression;
    }

    NodePointer emit_statement()
    {
        bool hidden = is(TokenType::HIDDEN_EMIT);
        auto node = make_node(NodeKind::Emit, next().position);
        node->is_hidden = hidden;
        const Token &name = expect(TokenType::IDENTIFIER);
        std::optional<unsigned> id = compilation.find_global_event(name.text);
        if (!id) {
            if (compilation.find_local_event(name.text))
                fail(name.position, name.text + " is a local event that you cannot emit");
            std::vector<std::string> names;
            for (const auto &event : compilation.definitions.events)
                names.push_back(event.name);
            fail(name.position,
                 with_suggestion(name.text + " is not a known event", name.text, names));
        }
        node->event_id = *id;
        unsigned declared = compilation.definitions.events[*id].size;
        if (declared == 0)
            return node;
        NodePointer argument = binary_or();
        if (is_direct_memory(*argument))
            check_constant_index(*argument); // the reference checks these while parsing
        unsigned size = vector_size(*argument);
        if (hidden && size > declared)
            fail(node->position,
                 "Event " + name.text + " needs an array of size " + std::to_string(declared) +
                   " or smaller, but one of size " + std::to_string(size) + " is passed");
        if (!hidden && size != declared)
            fail(node->position,
                 "Event " + name.text + " needs an array of size " + std::to_string(declared) +
                   ", but one of size " + std::to_string(size) + " is passed");
        node->size = size;
        if (is_direct_memory(*argument)) {
            node->children.push_back(std::move(argument));
        } else {
            unsigned address = 0;
            node->children.push_back(fill_temporary(std::move(argument), node->position, address));
            node->address = address;
        }
        return node;
    }

    NodePointer call_statement()
    {
        auto node = make_node(NodeKind::Call, next().position);
        const Token &name = expect(TokenType::IDENTIFIER);
        std::optional<unsigned> id = compilation.find_native(name.text);
        if (!id && name.text.rfind("vec.", 0) == 0) // the 2007 paper's name of math.*
            id = compilation.find_native("math." + name.text.substr(4));
        if (!id) {
            std::vector<std::string> names;
            for (const auto &native : compilation.target.native_functions)
                names.push_back(native.name);
            fail(
              node->position,
              with_suggestion("Target does not provide function " + name.text, name.text, names));
        }
        node->native_id = *id;
        const NativeFunction &native = compilation.target.native_functions[*id];
        const std::string &function = native.name;
        expect(TokenType::PAREN_OPEN);
        std::map<int, unsigned> template_sizes; // template id (negative) -> size
        std::vector<unsigned> any_sizes;
        if (native.parameters.empty() && !is(TokenType::PAREN_CLOSE))
            fail(position(), "Function " + function + " requires no argument, some are used");
        for (size_t i = 0; i < native.parameters.size(); ++i) {
            const NativeParameter &parameter = native.parameters[i];
            if (is(TokenType::PAREN_CLOSE))
                fail(position(),
                     "Function " + function + " requires " +
                       std::to_string(native.parameters.size()) + " arguments, only " +
                       std::to_string(i) + " are provided");
            SourcePosition argument_position = position();
            NodePointer argument = binary_or();
            // The reference checks, while parsing, the constant index of the
            // variable it meets first along the leftmost operands.
            const Node *leftmost = argument.get();
            while (leftmost->kind != NodeKind::Memory && !leftmost->children.empty())
                leftmost = leftmost->children[0].get();
            if (leftmost->kind == NodeKind::Memory)
                check_constant_index(*leftmost);
            unsigned size = vector_size(*argument);
            std::string which = "Argument " + std::to_string(i) + " (" + parameter.name +
                                ") of function " + function + " is of size " + std::to_string(size);
            if (parameter.size > 0 && size != static_cast<unsigned>(parameter.size))
                fail(argument_position,
                     which + ", function definition demands size " +
                       std::to_string(parameter.size));
            if (parameter.size < 0) {
                auto known = template_sizes.find(parameter.size);
                if (known == template_sizes.end())
                    template_sizes[parameter.size] = size;
                else if (known->second != size)
                    fail(argument_position,
                         which +
                           ", while a previous instance of the template parameter was of size " +
                           std::to_string(known->second));
            }
            if (parameter.size == 0)
                any_sizes.push_back(size);
            node->children.push_back(call_argument(std::move(argument), node->position));
            if (i + 1 < native.parameters.size() && !is(TokenType::PAREN_CLOSE))
                expect(TokenType::COMMA);
        }
        if (is(TokenType::COMMA))
            fail(position(),
                 "Function " + function + " requires " + std::to_string(native.parameters.size()) +
                   " arguments, more are used");
        expect(TokenType::PAREN_CLOSE);
        node->size_words = any_sizes;
        for (auto entry = template_sizes.rbegin(); entry != template_sizes.rend(); ++entry)
            node->size_words.push_back(entry->second); // -1 first, then -2, ...
        return node;
    }

    NodePointer call_argument(NodePointer argument, SourcePosition call_position)
    {
        auto node = make_node(NodeKind::CallArgument, argument->position);
        if (is_direct_memory(*argument)) {
            node->address_kind = ArgumentAddress::Direct;
            node->children.push_back(std::move(argument));
        } else if (argument->kind == NodeKind::Memory) {
            node->address_kind = ArgumentAddress::Computed;
            node->address = compilation.allocate_temporary(1, call_position);
            node->children.push_back(std::move(argument));
        } else {
            node->address_kind = ArgumentAddress::Temporary;
            unsigned address = 0;
            node->children.push_back(fill_temporary(std::move(argument), call_position, address));
            node->address = address;
        }
        return node;
    }

    NodePointer assignment()
    {
        if (!is(TokenType::IDENTIFIER))
            fail_expecting(TokenType::IDENTIFIER);
        NodePointer target = binary_or();
        SourcePosition where = position();
        int operation = -1;
        NodeKind kind = NodeKind::CompoundAssignment;
        switch (token().type) {
        case TokenType::ASSIGN: kind = NodeKind::Assignment; break;
        case TokenType::PLUS_PLUS:
            kind = NodeKind::IncrementAssignment;
            operation = VM_BINARY_ADD;
            break;
        case TokenType::MINUS_MINUS:
            kind = NodeKind::IncrementAssignment;
            operation = VM_BINARY_SUB;
            break;
        case TokenType::PLUS_EQUAL: operation = VM_BINARY_ADD; break;
        case TokenType::MINUS_EQUAL: operation = VM_BINARY_SUB; break;
        case TokenType::MULT_EQUAL: operation = VM_BINARY_MULT; break;
        case TokenType::DIV_EQUAL: operation = VM_BINARY_DIV; break;
        case TokenType::MOD_EQUAL: operation = VM_BINARY_MOD; break;
        case TokenType::SHIFT_LEFT_EQUAL: operation = VM_BINARY_SHIFT_LEFT; break;
        case TokenType::SHIFT_RIGHT_EQUAL: operation = VM_BINARY_SHIFT_RIGHT; break;
        case TokenType::BIT_OR_EQUAL: operation = VM_BINARY_BIT_OR; break;
        case TokenType::BIT_XOR_EQUAL: operation = VM_BINARY_BIT_XOR; break;
        case TokenType::BIT_AND_EQUAL: operation = VM_BINARY_BIT_AND; break;
        default: fail_expecting_assignment();
        }
        next();
        auto node = make_node(kind, where); // a target that is no variable fails when expanded
        node->operation = operation;
        node->children.push_back(std::move(target));
        if (kind != NodeKind::IncrementAssignment)
            node->children.push_back(binary_or());
        return node;
    }

    // --- expressions --------------------------------------------------------

    NodePointer binary(int operation, SourcePosition where, NodePointer left, NodePointer right)
    {
        auto node = make_node(NodeKind::Binary, where);
        node->operation = operation;
        node->height = std::max(left->height, right->height) + 1;
        if (node->height > MAX_EXPRESSION_HEIGHT)
            fail(where,
                 "This expression is too long or too deeply nested (more than " +
                   std::to_string(MAX_EXPRESSION_HEIGHT) + " levels)");
        node->children.push_back(std::move(left));
        node->children.push_back(std::move(right));
        return node;
    }

    NodePointer unary(int operation, SourcePosition where, NodePointer operand)
    {
        auto node = make_node(NodeKind::Unary, where);
        node->operation = operation;
        node->height = operand->height + 1;
        if (node->height > MAX_EXPRESSION_HEIGHT)
            fail(where,
                 "This expression is too long or too deeply nested (more than " +
                   std::to_string(MAX_EXPRESSION_HEIGHT) + " levels)");
        node->children.push_back(std::move(operand));
        return node;
    }

    NodePointer or_expression()
    {
        NodePointer left = and_expression();
        while (is(TokenType::OR)) {
            SourcePosition where = next().position;
            left = binary(VM_BINARY_OR, where, std::move(left), and_expression());
        }
        return left;
    }

    NodePointer and_expression()
    {
        NodePointer left = not_expression();
        while (is(TokenType::AND)) {
            SourcePosition where = next().position;
            left = binary(VM_BINARY_AND, where, std::move(left), not_expression());
        }
        return left;
    }

    NodePointer not_expression()
    {
        if (is(TokenType::NOT)) {
            NestingGuard guard(nesting, position());
            SourcePosition where = next().position;
            return unary(UNARY_NOT, where, not_expression());
        }
        return comparison();
    }

    NodePointer comparison()
    {
        NodePointer left = binary_or();
        while (true) {
            int operation = -1;
            switch (token().type) {
            case TokenType::EQUAL: operation = VM_BINARY_EQUAL; break;
            case TokenType::NOT_EQUAL: operation = VM_BINARY_NOT_EQUAL; break;
            case TokenType::BIGGER: operation = VM_BINARY_BIGGER_THAN; break;
            case TokenType::BIGGER_EQUAL: operation = VM_BINARY_BIGGER_EQUAL_THAN; break;
            case TokenType::SMALLER: operation = VM_BINARY_SMALLER_THAN; break;
            case TokenType::SMALLER_EQUAL: operation = VM_BINARY_SMALLER_EQUAL_THAN; break;
            default: return left;
            }
            SourcePosition where = next().position;
            left = binary(operation, where, std::move(left), binary_or());
        }
    }

    // One level of left-associative binary operators.
    template<typename Operand>
    NodePointer binary_level(std::initializer_list<std::pair<TokenType, int>> operators,
                             Operand operand)
    {
        NodePointer left = (this->*operand)();
        while (true) {
            auto match = std::find_if(operators.begin(),
                                      operators.end(),
                                      [this](const auto &entry) { return is(entry.first); });
            if (match == operators.end())
                return left;
            SourcePosition where = next().position;
            left = binary(match->second, where, std::move(left), (this->*operand)());
        }
    }

    NodePointer binary_or()
    {
        return binary_level({ { TokenType::BIT_OR, VM_BINARY_BIT_OR } }, &Parser::binary_xor);
    }
    NodePointer binary_xor()
    {
        return binary_level({ { TokenType::BIT_XOR, VM_BINARY_BIT_XOR } }, &Parser::binary_and);
    }
    NodePointer binary_and()
    {
        return binary_level({ { TokenType::BIT_AND, VM_BINARY_BIT_AND } }, &Parser::shift);
    }
    NodePointer shift()
    {
        return binary_level({ { TokenType::SHIFT_LEFT, VM_BINARY_SHIFT_LEFT },
                              { TokenType::SHIFT_RIGHT, VM_BINARY_SHIFT_RIGHT } },
                            &Parser::additive);
    }
    NodePointer additive()
    {
        return binary_level(
          { { TokenType::PLUS, VM_BINARY_ADD }, { TokenType::MINUS, VM_BINARY_SUB } },
          &Parser::multiplicative);
    }
    NodePointer multiplicative()
    {
        return binary_level({ { TokenType::MULT, VM_BINARY_MULT },
                              { TokenType::DIV, VM_BINARY_DIV },
                              { TokenType::MOD, VM_BINARY_MOD } },
                            &Parser::unary_expression);
    }

    // An element of a tuple or of a legacy list: a tuple alone (no operator
    // may follow it there), or an expression.
    NodePointer list_item()
    {
        if (is(TokenType::BRACKET_OPEN)) {
            NestingGuard guard(nesting, position());
            return tuple_expression();
        }
        return binary_or();
    }

    NodePointer tuple_expression()
    {
        auto tuple = make_node(NodeKind::Tuple, next().position);
        tuple->children.push_back(list_item());
        while (is(TokenType::COMMA)) {
            next();
            tuple->children.push_back(list_item());
        }
        expect(TokenType::BRACKET_CLOSE);
        for (const auto &element : tuple->children)
            tuple->height = std::max(tuple->height, element->height + 1);
        return tuple;
    }

    NodePointer unary_expression()
    {
        NestingGuard guard(nesting, position());
        SourcePosition where = position();
        switch (token().type) {
        case TokenType::PAREN_OPEN: {
            next();
            NodePointer inner = or_expression();
            expect(TokenType::PAREN_CLOSE);
            return inner;
        }
        case TokenType::BRACKET_OPEN: return tuple_expression();
        case TokenType::MINUS:
            next();
            if (is(TokenType::INTEGER)) { // a negative literal
                const Token &literal = next();
                int64_t value = -static_cast<int64_t>(literal.value);
                if (value < INT16_MIN_VALUE || value > INT16_MAX_VALUE)
                    fail(literal.position,
                         range_message(std::abs(value))); // the literal as written
                return immediate(value, literal.position);
            }
            return unary(VM_UNARY_SUB, where, unary_expression());
        case TokenType::BIT_NOT: next(); return unary(VM_UNARY_BIT_NOT, where, unary_expression());
        case TokenType::ABS: next(); return unary(VM_UNARY_ABS, where, unary_expression());
        case TokenType::INTEGER: {
            const Token &literal = next();
            if (literal.value > INT16_MAX_VALUE)
                fail(literal.position, range_message(literal.value));
            return immediate(literal.value, literal.position);
        }
        case TokenType::IDENTIFIER: {
            if (std::optional<int64_t> value = compilation.find_constant(token().text)) {
                next();
                return immediate(*value, where);
            }
            return variable_reference();
        }
        default:
            fail(where,
                 std::string("Expecting one of ") + OPERAND_LIST + "; but found " +
                   token_type_name(token().type) + " instead");
        }
    }

    NodePointer variable_reference()
    {
        const Token &name = next();
        const VariableInfo *variable = compilation.find_variable(name.text);
        if (variable == nullptr) {
            std::vector<std::string> names;
            for (const auto &known : compilation.variables)
                names.push_back(known.name);
            fail(name.position,
                 with_suggestion(name.text + " is not a defined variable", name.text, names));
        }
        auto node = make_node(NodeKind::Memory, name.position);
        node->name = variable->name;
        node->address = variable->address;
        node->variable_size = variable->size;
        if (!is(TokenType::BRACKET_OPEN))
            return node;
        next();
        NodePointer index = binary_or();
        std::optional<int64_t> first = evaluate_constant(*index);
        if (is(TokenType::COLON)) {
            if (!first)
                fail_expecting(TokenType::BRACKET_CLOSE);
            SourcePosition colon = next().position;
            NodePointer end_index = binary_or();
            SourcePosition after_end = position(); // the reference reports the token after j
            std::optional<int64_t> last = evaluate_constant(*end_index);
            if (!last)
                fail(colon, "Expecting a constant expression as a second index");
            if (*last < *first)
                fail(after_end,
                     "End of range index must be lower or equal to start of range index");
            expect(TokenType::BRACKET_CLOSE);
            node->index_form = IndexForm::Constant;
            node->first_index = static_cast<int>(*first);
            node->index_count = static_cast<int>(*last - *first + 1);
            node->is_slice = true;
            return node;
        }
        expect(TokenType::BRACKET_CLOSE);
        if (first) {
            node->index_form = IndexForm::Constant;
            node->first_index = static_cast<int>(*first);
            node->index_count = 1;
        } else {
            node->index_form = IndexForm::Expression;
            node->height = index->height + 1;
            node->children.push_back(std::move(index));
        }
        return node;
    }
};

} // namespace

NodePointer parse_program(const std::vector<Token> &tokens, Compilation &compilation)
{
    return Parser(tokens, compilation).program();
}

} // namespace aseba
