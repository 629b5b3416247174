// Code generation, exactly as the reference does it (language.md §8), and
// the stack depths it reports for the check of §11.3.

#include "codegen.hpp"

#include <algorithm>

#include "diagnostics.hpp"
#include "vm_opcodes.h"

namespace aseba
{

namespace
{

constexpr int64_t SMALL_IMMEDIATE_LIMIT = VM_SMALL_IMMEDIATE_LIMIT;
constexpr unsigned CONDITIONAL_BRANCH_WORDS = 2;
constexpr unsigned INIT_EVENT = VM_EVENT_INIT;

uint16_t opcode_word(int opcode, unsigned operand)
{
    return static_cast<uint16_t>((opcode << VM_OPCODE_SHIFT) | (operand & VM_OPERAND_MASK));
}

unsigned word_count(const Code &code)
{
    unsigned total = 0;
    for (const auto &instruction : code)
        total += instruction.word_count;
    return total;
}

void append(Code &code, const Code &more)
{
    code.insert(code.end(), more.begin(), more.end());
}

class Generator
{
  public:
    explicit Generator(const Compilation &state)
      : compilation(state)
    {
    }

    std::vector<Section> run(const Node &program)
    {
        Section init;
        init.event_id = INIT_EVENT;
        init.start = compilation.frames.front().start;
        sections.push_back(init);
        for (const auto &statement : program.children) {
            bool is_event = statement->kind == NodeKind::EventStart;
            if (is_event || statement->kind == NodeKind::SubStart) {
                sections.back().last_line = last_line;
                last_line = statement->position.line;
                Section section;
                section.is_subroutine = !is_event;
                section.start = statement->position;
                if (is_event)
                    section.event_id = statement->event_id;
                else
                    section.subroutine = *compilation.find_subroutine(statement->name);
                sections.push_back(section);
                continue;
            }
            statement_code(*statement, sections.back().code);
            unsigned depth = statement_depth(*statement, 0);
            Section &current = sections.back();
            if (depth > current.stack_depth) {
                current.stack_depth = depth;
                current.deepest_at = statement->position;
            }
        }
        sections.back().last_line = last_line;
        return std::move(sections); // the generator is done with them
    }

  private:
    const Compilation &compilation;
    std::vector<Section> sections;
    // The line the reference gives a section's final STOP: that of the last
    // instruction, or of the `end` of an if that was just generated.
    unsigned last_line = 0;

    static void add(Code &code, unsigned line, std::initializer_list<uint16_t> words)
    {
        code.push_back(make_instruction(words, line));
    }

    static void immediate(Code &code, int64_t value, unsigned line)
    {
        if (value > -SMALL_IMMEDIATE_LIMIT && value < SMALL_IMMEDIATE_LIMIT)
            add(code, line, { opcode_word(VM_OP_SMALL_IMMEDIATE, static_cast<unsigned>(value)) });
        else
            add(code,
                line,
                { opcode_word(VM_OP_LARGE_IMMEDIATE, 0), static_cast<uint16_t>(value & 0xFFFF) });
    }

    void expression_code(const Node &node, Code &code)
    {
        unsigned line = node.position.line;
        switch (node.kind) {
        case NodeKind::Immediate: immediate(code, node.value, line); break;
        case NodeKind::Load: add(code, line, { opcode_word(VM_OP_LOAD, node.address) }); break;
        case NodeKind::ArrayRead:
            expression_code(*node.children[0], code);
            add(code,
                line,
                { opcode_word(VM_OP_LOAD_INDIRECT, node.address),
                  static_cast<uint16_t>(node.variable_size) });
            break;
        case NodeKind::Binary:
            expression_code(*node.children[0], code);
            expression_code(*node.children[1], code);
            add(code,
                line,
                { opcode_word(VM_OP_BINARY_ARITHMETIC, static_cast<unsigned>(node.operation)) });
            break;
        case NodeKind::Unary:
            expression_code(*node.children[0], code);
            add(code,
                line,
                { opcode_word(VM_OP_UNARY_ARITHMETIC, static_cast<unsigned>(node.operation)) });
            break;
        case NodeKind::FunctionCall: {
            const Subroutine &called = call_code(node, code);
            add(
              code, line, { opcode_word(VM_OP_LOAD, compilation.local_address(called.frame, 0)) });
            break;
        }
        default:
            fail(node.position,
                 "Internal compiler error, please report a bug containing the "
                 "source which triggered this error");
        }
    }

    // The two operands and the operator of a condition (§8.3).
    const Node &condition_of(const Node &statement)
    {
        const Node &condition = *statement.children[0];
        if (condition.kind != NodeKind::Binary)
            fail(statement.position, "Expecting a condition, found a expression instead");
        return condition;
    }

    void statement_code(const Node &node, Code &code)
    {
        size_t before = code.size();
        statement_words(node, code);
        if (node.kind == NodeKind::If)
            last_line = node.end_line;
        else if (node.kind != NodeKind::Block && code.size() > before)
            last_line = code.back().line;
    }

    void statement_words(const Node &node, Code &code)
    {
        unsigned line = node.position.line;
        switch (node.kind) {
        case NodeKind::Block:
            for (const auto &child : node.children)
                statement_code(*child, code);
            break;
        case NodeKind::Assignment: {
            const Node &target = *node.children[0];
            expression_code(*node.children[1], code);
            if (target.kind == NodeKind::Store) {
                add(code, target.position.line, { opcode_word(VM_OP_STORE, target.address) });
            } else {
                expression_code(*target.children[0], code);
                add(code,
                    target.position.line,
                    { opcode_word(VM_OP_STORE_INDIRECT, target.address),
                      static_cast<uint16_t>(target.variable_size) });
            }
            break;
        }
        case NodeKind::If: {
            const Node &condition = condition_of(node);
            expression_code(*condition.children[0], code);
            expression_code(*condition.children[1], code);
            Code true_code, else_code;
            statement_code(*node.children[1], true_code);
            // the jump over the else takes the line of the last instruction before it
            unsigned jump_line = true_code.empty() ? line : true_code.back().line;
            statement_code(*node.children[2], else_code);
            bool has_else = node.has_else; // an empty `else` still gets its jump
            unsigned skip = CONDITIONAL_BRANCH_WORDS + word_count(true_code) + (has_else ? 1 : 0);
            unsigned branch = static_cast<unsigned>(condition.operation) |
                              (node.is_when ? VM_BRANCH_IS_WHEN_BIT : 0);
            add(code,
                line,
                { opcode_word(VM_OP_CONDITIONAL_BRANCH, branch), static_cast<uint16_t>(skip) });
            append(code, true_code);
            if (has_else) {
                add(code, jump_line, { opcode_word(VM_OP_JUMP, word_count(else_code) + 1) });
                append(code, else_code);
            }
            break;
        }
        case NodeKind::While: {
            const Node &condition = condition_of(node);
            Code condition_code, body;
            expression_code(*condition.children[0], condition_code);
            expression_code(*condition.children[1], condition_code);
            statement_code(*node.children[1], body);
            append(code, condition_code);
            unsigned skip = CONDITIONAL_BRANCH_WORDS + word_count(body) + 1;
            add(code,
                line,
                { opcode_word(VM_OP_CONDITIONAL_BRANCH, static_cast<unsigned>(condition.operation)),
                  static_cast<uint16_t>(skip) });
            append(code, body);
            int back = -static_cast<int>(word_count(condition_code) + CONDITIONAL_BRANCH_WORDS +
                                         word_count(body));
            add(code, line, { opcode_word(VM_OP_JUMP, static_cast<unsigned>(back)) });
            break;
        }
        case NodeKind::Emit:
            for (const auto &child : node.children)
                statement_code(*child, code);
            add(code,
                line,
                { opcode_word(VM_OP_EMIT, node.event_id),
                  static_cast<uint16_t>(node.size == 0 ? 0 : node.address),
                  static_cast<uint16_t>(node.size) });
            break;
        case NodeKind::Call: {
            for (auto size = node.size_words.rbegin(); size != node.size_words.rend(); ++size)
                immediate(code, *size, line);
            for (auto argument = node.children.rbegin(); argument != node.children.rend();
                 ++argument)
                argument_code(**argument, code, line);
            add(code, line, { opcode_word(VM_OP_NATIVE_CALL, node.native_id) });
            break;
        }
        case NodeKind::CallSub: {
            unsigned index = *compilation.find_subroutine(node.name);
            code.push_back(
              make_instruction({ opcode_word(VM_OP_SUB_CALL, 0) }, line, static_cast<int>(index)));
            break;
        }
        case NodeKind::FunctionCall: call_code(node, code); break;
        case NodeKind::Return:
            if (!node.children.empty()) { // the value goes in the frame's first word
                expression_code(*node.children[0], code);
                add(code, line, { opcode_word(VM_OP_STORE, node.address) });
            }
            add(code, line, { opcode_word(VM_OP_STOP, 0) });
            break;
        default: break;
        }
    }

    // The parameters given their values, then the call (docs/language.md).
    // When an argument calls a subroutine itself, that call could overwrite
    // parameters already given: then every value waits on the stack first.
    const Subroutine &call_code(const Node &call, Code &code)
    {
        unsigned index = *compilation.find_subroutine(call.name);
        const Subroutine &called = compilation.signatures[index];
        std::vector<unsigned> parameter_words;
        for (const auto &parameter : called.parameters)
            for (unsigned k = 0; k < parameter.size; ++k)
                parameter_words.push_back(
                  compilation.local_address(called.frame, parameter.offset + k));
        unsigned line = call.position.line;
        if (arguments_wait_on_stack(call)) {
            for (const auto &word : call.children)
                expression_code(*word, code);
            for (size_t k = parameter_words.size(); k-- > 0;)
                add(code, line, { opcode_word(VM_OP_STORE, parameter_words[k]) });
        } else {
            for (size_t k = 0; k < parameter_words.size(); ++k) {
                expression_code(*call.children[k], code);
                add(code, line, { opcode_word(VM_OP_STORE, parameter_words[k]) });
            }
        }
        code.push_back(
          make_instruction({ opcode_word(VM_OP_SUB_CALL, 0) }, line, static_cast<int>(index)));
        return called;
    }

    static bool arguments_wait_on_stack(const Node &call)
    {
        for (const auto &word : call.children)
            if (contains_call(*word))
                return true;
        return false;
    }

    void argument_code(const Node &argument, Code &code, unsigned line)
    {
        switch (argument.address_kind) {
        case ArgumentAddress::Direct: immediate(code, argument.address, line); break;
        case ArgumentAddress::Computed: {
            // index checked by LOAD_INDIRECT, then address = base + index (§8.7)
            unsigned base = argument.indexed_address;
            unsigned scratch = argument.address;
            expression_code(*argument.children[0], code);
            add(code, line, { opcode_word(VM_OP_STORE, scratch) });
            add(code, line, { opcode_word(VM_OP_LOAD, scratch) });
            add(code, line, { opcode_word(VM_OP_LOAD, scratch) });
            add(code,
                line,
                { opcode_word(VM_OP_LOAD_INDIRECT, base),
                  static_cast<uint16_t>(argument.variable_size) });
            add(code, line, { opcode_word(VM_OP_STORE, scratch) });
            immediate(code, base, line);
            add(code, line, { opcode_word(VM_OP_BINARY_ARITHMETIC, VM_BINARY_ADD) });
            break;
        }
        case ArgumentAddress::Temporary:
            statement_code(*argument.children[0], code);
            immediate(code, argument.address, line);
            break;
        }
    }

    // Stack words an expression needs (§11.3), with `below` words already in
    // use under it; records the calls it makes with the words under them.
    unsigned expression_depth(const Node &node, unsigned below)
    {
        switch (node.kind) {
        case NodeKind::Immediate:
        case NodeKind::Load: return 1;
        case NodeKind::Binary: {
            unsigned left = expression_depth(*node.children[0], below);
            return left + expression_depth(*node.children[1], below + left);
        }
        case NodeKind::Unary:
        case NodeKind::ArrayRead:
        case NodeKind::ArrayWrite: return expression_depth(*node.children[0], below);
        case NodeKind::FunctionCall: return std::max(call_depth(node, below), 1u); // the value
        default: return 0;
        }
    }

    unsigned call_depth(const Node &call, unsigned below)
    {
        bool waiting = arguments_wait_on_stack(call);
        unsigned depth = 0;
        for (size_t k = 0; k < call.children.size(); ++k) {
            auto waiting_words = static_cast<unsigned>(waiting ? k : 0);
            depth = std::max(
              depth, waiting_words + expression_depth(*call.children[k], below + waiting_words));
        }
        record_call(call.name, below, call.position);
        return depth;
    }

    void record_call(const std::string &name, unsigned below, SourcePosition where)
    {
        sections.back().calls.push_back({ *compilation.find_subroutine(name), below, where });
    }

    unsigned statement_depth(const Node &node, unsigned below)
    {
        switch (node.kind) {
        case NodeKind::Block:
        case NodeKind::Emit: {
            unsigned depth = 0;
            for (const auto &child : node.children)
                depth = std::max(depth, statement_depth(*child, below));
            return depth;
        }
        case NodeKind::Assignment: {
            // an indexed target's index is computed above the value
            unsigned value = expression_depth(*node.children[1], below);
            return std::max(expression_depth(*node.children[0], below + value), value);
        }
        case NodeKind::If:
        case NodeKind::While: {
            const Node &condition = *node.children[0];
            unsigned depth = 0;
            if (condition.kind == NodeKind::Binary) {
                unsigned left = expression_depth(*condition.children[0], below);
                depth = left + expression_depth(*condition.children[1], below + left);
            }
            for (size_t i = 1; i < node.children.size(); ++i)
                depth = std::max(depth, statement_depth(*node.children[i], below));
            return depth;
        }
        case NodeKind::Call: {
            unsigned depth = 0;
            auto size_words = static_cast<unsigned>(node.size_words.size());
            for (size_t i = 0; i < node.children.size(); ++i) {
                const Node &argument = *node.children[i];
                unsigned under = below + size_words + static_cast<unsigned>(i);
                unsigned argument_depth = 1;
                if (argument.address_kind == ArgumentAddress::Computed)
                    argument_depth = std::max(expression_depth(*argument.children[0], under), 2u);
                else if (argument.address_kind == ArgumentAddress::Temporary)
                    argument_depth = std::max(statement_depth(*argument.children[0], under), 1u);
                depth = std::max(depth, size_words + static_cast<unsigned>(i) + argument_depth);
            }
            return depth;
        }
        case NodeKind::CallSub: record_call(node.name, below, node.position); return 0;
        case NodeKind::FunctionCall: return call_depth(node, below);
        case NodeKind::Return:
            return node.children.empty() ? 0 : expression_depth(*node.children[0], below);
        default: return 0;
        }
    }
};

} // namespace

std::vector<Section> generate_code(const Node &program, const Compilation &compilation)
{
    return Generator(compilation).run(program);
}

} // namespace aseba
