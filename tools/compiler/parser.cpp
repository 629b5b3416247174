// The recursive-descent parser of language.md §3-§4 and of the additions of
// docs/language.md. Besides building the tree it does what the reference does
// while parsing: declares constants and variables, resolves names, events and
// natives, and allocates the temporaries of `emit` and native-call arguments
// (§7). It also gives locals and parameters their offsets in the frame of
// their handler or subroutine, block by block, and records each call with
// the frame words in use around it (locals.cpp lays the frames out).

#include <algorithm>

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
                       " levels of blocks, elseif, parentheses and unary operators): move inner "
                       "parts into subroutines");
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
             std::string("Expecting ") + token_type_name(expected) + ", found " + found() +
               " instead");
    }
    const Token &expect(TokenType type)
    {
        if (!is(type))
            fail_expecting(type);
        return next();
    }

    const Token &peek(size_t offset) const
    {
        return tokens[std::min(current + offset, tokens.size() - 1)];
    }

    // --- locals and frames --------------------------------------------------

    // A variable as a reference sees it: a global (frame -1) or a local.
    struct Variable {
        std::string name;
        unsigned address = 0; // globals: absolute; locals: offset in their frame
        unsigned size = 1;
        int frame = -1;
    };

    std::vector<Variable> visible_locals; // innermost last
    unsigned frame_offset = 0;            // words of the current frame held by visible locals
    unsigned statement_scratch = 0;       // words of the frame taken by this statement's scratch
    std::vector<size_t> pending_calls;    // call sites whose words in use are not known yet
    int current_subroutine = -1;          // index in compilation.signatures, in a subroutine

    unsigned current_frame() const
    {
        return static_cast<unsigned>(compilation.frames.size() - 1);
    }

    bool in_subroutine_with_parameter_list() const
    {
        return current_subroutine >= 0 &&
               compilation.signatures[static_cast<size_t>(current_subroutine)].has_parameter_list;
    }

    std::optional<Variable> lookup_variable(const std::string &name) const
    {
        for (auto local = visible_locals.rbegin(); local != visible_locals.rend(); ++local)
            if (local->name == name)
                return *local;
        if (const VariableInfo *global = compilation.find_variable(name))
            return Variable{ global->name, global->address, global->size, -1 };
        return std::nullopt;
    }

    std::vector<std::string> variable_names() const
    {
        std::vector<std::string> names;
        for (const auto &known : compilation.variables)
            names.push_back(known.name);
        for (const auto &local : visible_locals)
            names.push_back(local.name);
        return names;
    }

    // Records that the current frame has `frame_offset + statement_scratch`
    // words in use, reached at `where`.
    void note_frame_use(SourcePosition where)
    {
        // one frame alone beyond the memory: no need to read further
        if (compilation.next_free_address + frame_offset + statement_scratch >
            compilation.target.variables_size)
            fail(where,
                 "Not enough variable memory for the locals: " +
                   std::to_string(compilation.next_free_address) + " words of globals and " +
                   std::to_string(frame_offset + statement_scratch) + " of locals in " +
                   compilation.frames.back().title + ", the target has " +
                   std::to_string(compilation.target.variables_size) +
                   " (use fewer or smaller locals)");
        Frame &frame = compilation.frames.back();
        if (frame_offset + statement_scratch > frame.size) {
            frame.size = frame_offset + statement_scratch;
            frame.largest_at = where;
        }
    }

    // Declares a local (or parameter) of `size` words in the current frame.
    Variable declare_local(const Token &name, unsigned size)
    {
        Variable local{ name.text, frame_offset, size, static_cast<int>(current_frame()) };
        frame_offset += size;
        note_frame_use(name.position);
        visible_locals.push_back(local);
        compilation.locals.push_back({ name.text, current_frame(), local.address, size });
        return local;
    }

    // The calls parsed since the last flush happen while `frame_offset +
    // statement_scratch` words of this frame are in use.
    void flush_calls()
    {
        for (size_t index : pending_calls)
            compilation.frames.back().calls[index].words_in_use = frame_offset + statement_scratch;
        pending_calls.clear();
    }

    // `size` scratch words for this statement: at the end of memory as in
    // Aseba 1.6, or in the frame when a call in the statement could
    // overwrite them there (docs/language.md). Sets `frame` accordingly.
    unsigned scratch(unsigned size, SourcePosition where, bool in_frame, int &frame)
    {
        if (!in_frame) {
            frame = -1;
            return compilation.allocate_temporary(size, where);
        }
        unsigned offset = frame_offset + statement_scratch;
        statement_scratch += size;
        note_frame_use(where);
        frame = static_cast<int>(current_frame());
        return offset;
    }

    void start_frame(const std::string &title, SourcePosition where)
    {
        Frame frame;
        frame.title = title;
        frame.start = where;
        compilation.frames.push_back(frame);
        visible_locals.clear();
        frame_offset = 0;
        current_subroutine = -1;
    }

    // --- definitions --------------------------------------------------------

    // The current token as messages name it: its kind, and for names and
    // numbers what is written.
    std::string found() const
    {
        const Token &shown = token();
        std::string text = token_type_name(shown.type);
        if (shown.type == TokenType::IDENTIFIER || shown.type == TokenType::INTEGER)
            text += " " + shown.text;
        return text;
    }

    [[noreturn]] void fail_expecting_assignment() const
    {
        fail(position(),
             "Expecting an assignment (=, +=, -=, ..., ++ or --) after the variable, found " +
               found() + " instead");
    }

    // A statement cannot start with the current token.
    [[noreturn]] void fail_expecting_statement() const
    {
        std::string hint;
        if (is(TokenType::CONST))
            hint = " (constants are defined at the start of the program, before the variables)";
        else if (is(TokenType::VAR))
            hint = " (inside a block, declare variables with local)";
        else if (is(TokenType::EQUAL) || is(TokenType::NOT_EQUAL) || is(TokenType::BIGGER) ||
                 is(TokenType::BIGGER_EQUAL) || is(TokenType::SMALLER) ||
                 is(TokenType::SMALLER_EQUAL))
            hint = " (comparisons are only allowed in the conditions of if, elseif, when and "
                   "while)";
        fail(position(),
             "Expecting a statement (an assignment, if, when, while, for, emit, call, a "
             "subroutine call, return or local), found " +
               found() + " instead" + hint);
    }

    // The name of a `const` definition.
    const Token &defined_name()
    {
        if (!is(TokenType::IDENTIFIER))
            fail(position(),
                 "Expecting a constant name after const, found " + found() + " instead");
        return next();
    }

    void constant_definition()
    {
        next();
        const Token &name = defined_name();
        if (compilation.find_constant(name.text))
            fail(name.position, "Constant " + name.text + " is already defined");
        if (!is(TokenType::ASSIGN))
            fail(position(),
                 "Expecting = (assignation) after the constant's name, found " + found() +
                   " instead");
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

    // The name of a `var`, `local` or parameter, which must be new here.
    const Token &new_variable_name(const char *after)
    {
        if (!is(TokenType::IDENTIFIER))
            fail(position(),
                 std::string("Expecting a variable name after ") + after + ", found " + found() +
                   " instead");
        const Token &name = next();
        if (lookup_variable(name.text))
            fail(name.position, "Variable " + name.text + " is already defined");
        if (compilation.find_constant(name.text))
            fail(name.position, "Variable " + name.text + " has the same name as a constant");
        return name;
    }

    // `[size]` after a variable's name: the size, or nothing for `[]`.
    std::optional<int64_t> declared_array_size()
    {
        SourcePosition bracket = next().position;
        std::optional<int64_t> size;
        if (!is(TokenType::BRACKET_CLOSE)) {
            NodePointer size_expression = binary_or();
            std::optional<int64_t> value = evaluate_constant(*size_expression, true);
            if (!value) {
                check_constant_indexes(*size_expression); // the reference's order
                fail(bracket, "Not a valid constant expression");
            }
            if (*value < 0)
                fail(bracket, "Array size: result is negative (" + std::to_string(*value) + ")");
            if (*value == 0)
                fail(bracket, "Array size: result is null");
            size = value;
        }
        expect(TokenType::BRACKET_CLOSE);
        return size;
    }

    // What `var` and `local` declare: a name, a size and maybe a value.
    struct Declaration {
        const Token *name = nullptr;
        unsigned size = 1;
        NodePointer initializer;
        SourcePosition assign_position;
    };

    Declaration declaration(const char *keyword)
    {
        next();
        Declaration result;
        result.name = &new_variable_name(keyword);
        int64_t declared_size = 1;
        bool size_known = true;
        if (is(TokenType::BRACKET_OPEN)) {
            std::optional<int64_t> size = declared_array_size();
            size_known = size.has_value();
            declared_size = size.value_or(1);
        }
        if (is(TokenType::ASSIGN)) {
            result.assign_position = next().position;
            result.initializer = initial_value();
        }
        if (!size_known) {
            if (!result.initializer)
                fail(result.name->position, "Array " + result.name->text + " has undefined size");
            declared_size = vector_size(*result.initializer);
        }
        if (declared_size > compilation.target.variables_size)
            fail(result.name->position, "No more free variable space");
        result.size = static_cast<unsigned>(declared_size);
        flush_calls(); // the value is computed before the variable exists
        return result;
    }

    // The assignment of a declaration's initial value to `variable`.
    static NodePointer initial_assignment(Declaration &declared, const Variable &variable)
    {
        if (!declared.initializer)
            return nullptr;
        auto target = make_node(NodeKind::Memory, declared.name->position);
        target->name = variable.name;
        target->address = variable.address;
        target->variable_size = variable.size;
        target->frame = variable.frame;
        auto assignment = make_node(NodeKind::Assignment, declared.assign_position);
        assignment->children.push_back(std::move(target));
        assignment->children.push_back(std::move(declared.initializer));
        return assignment;
    }

    NodePointer variable_definition()
    {
        Declaration declared = declaration("var");
        const Token &name = *declared.name;
        if (compilation.next_free_address + declared.size > compilation.target.variables_size)
            fail(name.position, "No more free variable space");
        Variable global{ name.text, compilation.next_free_address, declared.size, -1 };
        compilation.add_variable(
          { name.text, static_cast<uint16_t>(global.address), static_cast<uint16_t>(global.size) });
        compilation.next_free_address += declared.size;
        return initial_assignment(declared, global);
    }

    NodePointer local_declaration()
    {
        Declaration declared = declaration("local");
        Variable local = declare_local(*declared.name, declared.size);
        return initial_assignment(declared, local);
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

    // The name after `onevent`, `sub`, `callsub`, `emit`, `call` or `for`.
    const Token &name_after(const char *keyword, const char *what)
    {
        if (!is(TokenType::IDENTIFIER))
            fail(position(),
                 std::string("Expecting ") + what + " after " + keyword + ", found " + found() +
                   " instead");
        return next();
    }

    NodePointer event_start()
    {
        next();
        const Token &name = name_after("onevent", "an event name");
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
        start_frame("onevent " + name.text, name.position);
        auto marker = make_node(NodeKind::EventStart, name.position);
        marker->event_id = *id;
        return marker;
    }

    NodePointer subroutine_start()
    {
        next();
        const Token &name = name_after("sub", "a subroutine name");
        if (compilation.find_subroutine(name.text))
            fail(name.position, "Subroutine " + name.text + " is already defined");
        start_frame("sub " + name.text, name.position);
        compilation.subroutine_index[name.text] =
          static_cast<unsigned>(compilation.subroutines.size());
        compilation.subroutines.push_back(name.text);
        Subroutine subroutine;
        subroutine.name = name.text;
        subroutine.position = name.position;
        subroutine.frame = current_frame();
        if (is(TokenType::PAREN_OPEN)) {
            next();
            subroutine.has_parameter_list = true;
            while (!is(TokenType::PAREN_CLOSE)) {
                const Token &parameter = new_variable_name("( or , in a parameter list");
                unsigned size = 1;
                if (is(TokenType::BRACKET_OPEN)) {
                    SourcePosition bracket = position();
                    std::optional<int64_t> declared = declared_array_size();
                    if (!declared)
                        fail(bracket, "A parameter needs a size: write " + parameter.text + "[N]");
                    if (*declared > compilation.target.variables_size)
                        fail(parameter.position, "No more free variable space");
                    size = static_cast<unsigned>(*declared);
                }
                Variable local = declare_local(parameter, size);
                subroutine.parameters.push_back({ parameter.text, size, local.address });
                if (is(TokenType::COMMA))
                    next();
                else if (!is(TokenType::PAREN_CLOSE))
                    fail(position(),
                         "Expecting , (comma) or ) (close parenthesis) in the parameter list, "
                         "found " +
                           found() + " instead");
            }
            next();
        }
        compilation.signatures.push_back(subroutine);
        current_subroutine = static_cast<int>(compilation.signatures.size() - 1);
        auto marker = make_node(NodeKind::SubStart, name.position);
        marker->name = name.text;
        return marker;
    }

    // --- statements ---------------------------------------------------------

    static bool can_start_expression(TokenType type)
    {
        switch (type) {
        case TokenType::IDENTIFIER:
        case TokenType::INTEGER:
        case TokenType::PAREN_OPEN:
        case TokenType::BRACKET_OPEN:
        case TokenType::MINUS:
        case TokenType::BIT_NOT:
        case TokenType::ABS: return true;
        default: return false;
        }
    }

    // Tokens after which no statement of the current block follows.
    bool at_block_end() const
    {
        switch (token().type) {
        case TokenType::END:
        case TokenType::ELSE:
        case TokenType::ELSEIF:
        case TokenType::ONEVENT:
        case TokenType::SUB:
        case TokenType::END_OF_STREAM: return true;
        default: return false;
        }
    }

    NodePointer statement()
    {
        NestingGuard guard(nesting, position());
        NodePointer node = statement_of_kind();
        flush_calls();
        statement_scratch = 0;
        return node;
    }

    NodePointer statement_of_kind()
    {
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
            if (is(TokenType::IDENTIFIER) && peek(1).type == TokenType::PAREN_OPEN)
                return function_call(true);
            const Token &name = name_after("callsub", "a subroutine name");
            auto call = make_node(NodeKind::CallSub, where);
            call->name = name.text;
            record_call(name.text, where);
            return call;
        }
        case TokenType::RETURN: return return_statement();
        case TokenType::IDENTIFIER:
            // `local x` and `f(...)` are errors in Aseba 1.6: a name is never
            // followed by a name or a parenthesis there
            if (token().text == "local" && peek(1).type == TokenType::IDENTIFIER)
                return local_declaration();
            if (peek(1).type == TokenType::PAREN_OPEN)
                return function_call(true);
            return assignment();
        default: fail_expecting_statement();
        }
    }

    NodePointer return_statement()
    {
        auto node = make_node(NodeKind::Return, next().position);
        if (!in_subroutine_with_parameter_list()) {
            // Aseba 1.6: a `return` alone; a name after it starts the next
            // statement, anything else that could be a value cannot
            if (can_start_expression(token().type) && !is(TokenType::IDENTIFIER))
                fail(position(),
                     "Expecting a statement after return, found " + found() +
                       " instead: only a subroutine written with parentheses, sub NAME(...), "
                       "returns a value");
            return node;
        }
        Subroutine &subroutine = compilation.signatures[static_cast<size_t>(current_subroutine)];
        if (can_start_expression(token().type)) {
            node->children.push_back(binary_or());
            node->frame = static_cast<int>(current_frame());
            node->address = 0; // the value goes in the first word of the frame
            subroutine.valued_returns.push_back(node->position);
        } else {
            subroutine.bare_returns.push_back(node->position);
        }
        if (!at_block_end())
            fail(position(),
                 "Expecting the end of the block after return (end, else, elseif, or the next "
                 "onevent or sub), found " +
                   found() + " instead: code after a return would never run");
        return node;
    }

    // `name(arguments)`, a statement or an expression.
    NodePointer function_call(bool is_statement)
    {
        const Token &name = next();
        auto node = make_node(NodeKind::FunctionCall, name.position);
        node->name = name.text;
        node->is_statement = is_statement;
        next(); // (
        while (!is(TokenType::PAREN_CLOSE)) {
            NodePointer argument = binary_or();
            node->height = std::max(node->height, argument->height + 1);
            node->children.push_back(std::move(argument));
            if (is(TokenType::COMMA))
                next();
            else if (!is(TokenType::PAREN_CLOSE))
                fail(position(),
                     "Expecting , (comma) or ) (close parenthesis) in the arguments of " +
                       name.text + ", found " + found() + " instead");
        }
        next();
        check_height(*node);
        record_call(name.text, name.position);
        return node;
    }

    void record_call(const std::string &callee, SourcePosition where)
    {
        auto &calls = compilation.frames.back().calls;
        calls.push_back({ callee, 0, where });
        pending_calls.push_back(calls.size() - 1);
    }

    // Statements until one of the `enders` (not consumed); the block's locals
    // end with it.
    NodePointer block(std::initializer_list<TokenType> enders,
                      const char *opener,
                      SourcePosition opened_at)
    {
        auto result = make_node(NodeKind::Block, position());
        size_t visible = visible_locals.size();
        unsigned offset = frame_offset;
        while (std::find(enders.begin(), enders.end(), token().type) == enders.end()) {
            if (is(TokenType::END_OF_STREAM) || is(TokenType::ONEVENT) || is(TokenType::SUB) ||
                is(TokenType::END) || is(TokenType::ELSE) || is(TokenType::ELSEIF))
                fail(position(),
                     std::string("Expecting ") + token_type_name(*enders.begin()) +
                       " to close the " + opener + " of line " + std::to_string(opened_at.line) +
                       ", found " + found() + " instead");
            add(*result, statement());
        }
        visible_locals.resize(visible);
        frame_offset = offset;
        return result;
    }

    NodePointer if_statement()
    {
        // an `elseif` nests one more `if` without passing through statement():
        // it counts against the nesting limit here
        bool is_elseif = is(TokenType::ELSEIF);
        std::optional<NestingGuard> guard;
        if (is_elseif)
            guard.emplace(nesting, position());
        auto node = make_node(NodeKind::If, next().position);
        node->children.reserve(3); // condition, true block, else block
        node->children.push_back(or_expression());
        flush_calls();
        expect(TokenType::THEN);
        const char *opener = is_elseif ? "elseif" : "if";
        node->children.push_back(
          block({ TokenType::END, TokenType::ELSE, TokenType::ELSEIF }, opener, node->position));
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
            SourcePosition else_position = next().position;
            node->children.push_back(block({ TokenType::END }, "else", else_position));
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
        flush_calls();
        expect(TokenType::DO);
        node->children.push_back(
          block({ TokenType::END, TokenType::ELSE, TokenType::ELSEIF }, "when", node->position));
        node->children.push_back(make_node(NodeKind::Block, position()));
        node->end_line = expect(TokenType::END).position.line;
        return node;
    }

    NodePointer while_statement()
    {
        auto node = make_node(NodeKind::While, next().position);
        node->children.reserve(2);
        node->children.push_back(or_expression());
        flush_calls();
        expect(TokenType::DO);
        node->children.push_back(block({ TokenType::END }, "while", node->position));
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
                fail(literal.position, literal_range_message(literal, true));
            return { value, literal.position };
        }
        if (is(TokenType::INTEGER)) {
            const Token &literal = next();
            if (literal.value > INT16_MAX_VALUE)
                fail(literal.position, literal_range_message(literal, false));
            return { literal.value, where };
        }
        if (!is(TokenType::IDENTIFIER))
            fail(position(),
                 "Expecting an integer or a constant's name, found " + found() + " instead");
        const Token &name = next();
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
            name_after("for", "a variable");
        NodePointer variable = variable_reference();
        flush_calls();
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
        NodePointer body = block({ TokenType::END }, "for", for_position);
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

    // A Memory node for `size` words of scratch at `address` (in `frame`).
    static NodePointer temporary(unsigned address, unsigned size, int frame, SourcePosition where)
    {
        auto node = make_node(NodeKind::Memory, where);
        node->name = TEMPORARY_NAME;
        node->address = address;
        node->variable_size = size;
        node->frame = frame;
        return node;
    }

    // An assignment of `value` to fresh scratch words of its size, allocated
    // now (in the frame if `in_frame`); `holder` receives where they are.
    NodePointer fill_temporary(NodePointer value, SourcePosition where, bool in_frame, Node &holder)
    {
        unsigned size = vector_size(*value);
        holder.address = scratch(size, where, in_frame, holder.frame);
        auto assignment = make_node(NodeKind::Assignment, where);
        assignment->children.push_back(temporary(holder.address, size, holder.frame, where));
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
        const Token &name = name_after(hidden ? "_emit" : "emit", "an event name");
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
            bool in_frame = contains_call(*argument);
            node->children.push_back(
              fill_temporary(std::move(argument), node->position, in_frame, *node));
        }
        return node;
    }

    NodePointer call_statement()
    {
        auto node = make_node(NodeKind::Call, next().position);
        const Token &name = name_after("call", "a native function name");
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
        // arguments are filled last first: from the first one with a call
        // on, their scratch must survive that call
        bool after_call = false;
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
            // the start of a size error, built only when one is found
            auto which = [&] {
                return "Argument " + std::to_string(i) + " (" + parameter.name + ") of function " +
                       function + " is of size " + std::to_string(size);
            };
            if (parameter.size > 0 && size != static_cast<unsigned>(parameter.size))
                fail(argument_position,
                     which() + ", function definition demands size " +
                       std::to_string(parameter.size));
            if (parameter.size < 0) {
                auto known = template_sizes.find(parameter.size);
                if (known == template_sizes.end())
                    template_sizes[parameter.size] = size;
                else if (known->second != size)
                    fail(argument_position,
                         which() +
                           ", while a previous instance of the template parameter was of size " +
                           std::to_string(known->second));
            }
            if (parameter.size == 0)
                any_sizes.push_back(size);
            after_call = after_call || contains_call(*argument);
            node->children.push_back(
              call_argument(std::move(argument), node->position, after_call));
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

    NodePointer call_argument(NodePointer argument, SourcePosition call_position, bool in_frame)
    {
        auto node = make_node(NodeKind::CallArgument, argument->position);
        if (is_direct_memory(*argument)) {
            node->address_kind = ArgumentAddress::Direct;
            node->children.push_back(std::move(argument));
        } else if (argument->kind == NodeKind::Memory) {
            node->address_kind = ArgumentAddress::Computed;
            node->address = scratch(1, call_position, in_frame, node->frame);
            node->children.push_back(std::move(argument));
        } else {
            node->address_kind = ArgumentAddress::Temporary;
            node->children.push_back(
              fill_temporary(std::move(argument), call_position, in_frame, *node));
        }
        return node;
    }

    NodePointer assignment()
    {
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
        node->children.reserve(2);
        node->children.push_back(std::move(target));
        if (kind != NodeKind::IncrementAssignment)
            node->children.push_back(binary_or());
        reserve_vector_temporary(*node);
        return node;
    }

    // A vector assignment that reads its own variable goes through a
    // temporary (§8.1); with a call in its value, that temporary must
    // survive the call, so it is taken in the frame now.
    void reserve_vector_temporary(Node &assignment)
    {
        if (assignment.children.size() < 2 || !contains_call(*assignment.children[1]))
            return;
        const Node &target = *assignment.children[0];
        if (target.kind != NodeKind::Memory)
            return;
        unsigned size = vector_size(target);
        bool reads_itself =
          assignment.kind != NodeKind::Assignment || mentions(*assignment.children[1], target.name);
        if (size > 1 && reads_itself) {
            assignment.address = scratch(size, assignment.position, true, assignment.frame);
            assignment.has_reserved_temporary = true;
        }
    }

    // --- expressions --------------------------------------------------------

    static void check_height(const Node &node)
    {
        if (node.height > MAX_EXPRESSION_HEIGHT)
            fail(node.position,
                 "This expression is too long or too deeply nested (more than " +
                   std::to_string(MAX_EXPRESSION_HEIGHT) +
                   " levels): split it into several statements");
    }

    NodePointer binary(int operation, SourcePosition where, NodePointer left, NodePointer right)
    {
        auto node = make_node(NodeKind::Binary, where);
        node->operation = operation;
        node->height = std::max(left->height, right->height) + 1;
        check_height(*node);
        node->children.reserve(2);
        node->children.push_back(std::move(left));
        node->children.push_back(std::move(right));
        return node;
    }

    NodePointer unary(int operation, SourcePosition where, NodePointer operand)
    {
        auto node = make_node(NodeKind::Unary, where);
        node->operation = operation;
        node->height = operand->height + 1;
        check_height(*node);
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
                    fail(literal.position, literal_range_message(literal, true));
                return immediate(value, literal.position);
            }
            return unary(VM_UNARY_SUB, where, unary_expression());
        case TokenType::BIT_NOT: next(); return unary(VM_UNARY_BIT_NOT, where, unary_expression());
        case TokenType::ABS: next(); return unary(VM_UNARY_ABS, where, unary_expression());
        case TokenType::INTEGER: {
            const Token &literal = next();
            if (literal.value > INT16_MAX_VALUE)
                fail(literal.position, literal_range_message(literal, false));
            return immediate(literal.value, literal.position);
        }
        case TokenType::IDENTIFIER: {
            if (peek(1).type == TokenType::PAREN_OPEN)
                return function_call(false);
            if (std::optional<int64_t> value = compilation.find_constant(token().text)) {
                next();
                return immediate(*value, where);
            }
            return variable_reference();
        }
        default:
            fail(where,
                 "Expecting a value (a number, a name, ( (open parenthesis), [ (open bracket), "
                 "- (minus), ~ or abs), found " +
                   found() + " instead");
        }
    }

    NodePointer variable_reference()
    {
        const Token &name = next();
        std::optional<Variable> variable = lookup_variable(name.text);
        if (!variable)
            fail(name.position,
                 with_suggestion(
                   name.text + " is not a defined variable", name.text, variable_names()));
        auto node = make_node(NodeKind::Memory, name.position);
        node->name = variable->name;
        node->address = variable->address;
        node->variable_size = variable->size;
        node->frame = variable->frame;
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
