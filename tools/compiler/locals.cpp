// Subroutine calls and the locals area (docs/language.md): checks calls and
// returns against the subroutines' parameter lists, gives every frame (the
// init code, a handler, a subroutine) its place in the area and makes every
// frame-relative address absolute. Handlers never run at the same time, so
// their frames all start at the area's start; a subroutine's frame goes
// after the words its callers hold at each call.

#include "compilation.hpp"
#include "diagnostics.hpp"

namespace aseba
{

namespace
{

// Whether running `statement` always ends in a `return`.
bool always_returns(const Node &statement)
{
    switch (statement.kind) {
    case NodeKind::Return: return true;
    case NodeKind::Block:
        for (const auto &child : statement.children)
            if (always_returns(*child))
                return true;
        return false;
    case NodeKind::If:
        return !statement.is_when && statement.has_else && always_returns(*statement.children[1]) &&
               always_returns(*statement.children[2]);
    default: return false;
    }
}

std::string line_text(SourcePosition position)
{
    return "line " + std::to_string(position.line);
}

// Checks every call of a subroutine with arguments, and every `return e`.
void check_calls(const Node &node, const Compilation &compilation)
{
    if (node.kind == NodeKind::FunctionCall) {
        const Subroutine &called = compilation.called_subroutine(
          node.name, node.position, "Subroutine " + node.name + " is not defined");
        if (!node.is_statement && !called.returns_value())
            fail(node.position,
                 "Subroutine " + node.name +
                   " returns no value, so it cannot be used in an expression (call it as a "
                   "statement, or make it end with return and a value)");
        size_t expected = called.parameters.size();
        if (node.children.size() != expected)
            fail(node.position,
                 "Subroutine " + node.name + " takes " + std::to_string(expected) +
                   (expected == 1 ? " argument" : " arguments") + ", " +
                   std::to_string(node.children.size()) + " given");
        for (size_t i = 0; i < expected; ++i) {
            const Subroutine::Parameter &parameter = called.parameters[i];
            unsigned size = vector_size(*node.children[i]);
            if (size != parameter.size)
                fail(node.children[i]->position,
                     "Argument " + std::to_string(i + 1) + " (" + parameter.name + ") of " +
                       node.name + " is of size " + std::to_string(size) +
                       ", the parameter is of size " + std::to_string(parameter.size));
        }
    }
    if (node.kind == NodeKind::Return && !node.children.empty()) {
        unsigned size = vector_size(*node.children[0]);
        if (size != 1)
            fail(node.position,
                 "A subroutine returns a single value, not an array of size " +
                   std::to_string(size));
    }
    for (const auto &child : node.children)
        check_calls(*child, compilation);
}

// Checks that a subroutine returning a value returns one on every path.
void check_returns(const Node &program, const Compilation &compilation)
{
    size_t section = 0; // 0: the init code, then one per marker
    std::vector<bool> ends_with_return(compilation.frames.size(), false);
    for (const auto &statement : program.children) {
        if (statement->kind == NodeKind::EventStart || statement->kind == NodeKind::SubStart)
            ++section;
        else if (always_returns(*statement))
            ends_with_return[section] = true;
    }
    for (const Subroutine &subroutine : compilation.signatures) {
        if (!subroutine.returns_value())
            continue;
        if (!subroutine.bare_returns.empty())
            fail(subroutine.bare_returns.front(),
                 "Subroutine " + subroutine.name + " returns a value (" +
                   line_text(subroutine.valued_returns.front()) +
                   "), so this return needs one too");
        if (!ends_with_return[subroutine.frame])
            fail(subroutine.position,
                 "Subroutine " + subroutine.name +
                   " can reach its end without returning a value: end it with return and a "
                   "value");
    }
}

// Every frame's place in the locals area: a subroutine's frame starts after
// the words its callers use at the calls. Frames are placed callers first
// (Kahn's order on the calls); frames in a cycle of calls keep base 0, as
// the stack check refuses the recursion anyway.
void lay_out_frames(Compilation &compilation)
{
    std::vector<Frame> &frames = compilation.frames;
    std::vector<std::vector<std::pair<size_t, unsigned>>> callees(frames.size()); // frame, words
    std::vector<unsigned> callers(frames.size(), 0);
    for (size_t f = 0; f < frames.size(); ++f) {
        for (const Frame::CallSite &call : frames[f].calls) {
            std::optional<unsigned> index = compilation.find_subroutine(call.callee);
            if (!index)
                continue; // reported by the type check
            size_t called = compilation.signatures[*index].frame;
            callees[f].push_back({ called, call.words_in_use });
            ++callers[called];
        }
    }
    std::vector<size_t> ready;
    for (size_t f = 0; f < frames.size(); ++f)
        if (callers[f] == 0)
            ready.push_back(f);
    while (!ready.empty()) {
        size_t f = ready.back();
        ready.pop_back();
        for (const auto &[called, words_in_use] : callees[f]) {
            frames[called].base = std::max(frames[called].base, frames[f].base + words_in_use);
            if (--callers[called] == 0)
                ready.push_back(called);
        }
    }
    compilation.locals_start = compilation.next_free_address;
    compilation.locals_size = 0;
    for (const Frame &frame : frames)
        compilation.locals_size = std::max(compilation.locals_size, frame.base + frame.size);
}

void make_addresses_absolute(Node &node, const Compilation &compilation)
{
    if (node.frame >= 0) {
        node.address = compilation.local_address(static_cast<unsigned>(node.frame), node.address);
        node.frame = -1;
    }
    for (auto &child : node.children)
        make_addresses_absolute(*child, compilation);
}

} // namespace

void allocate_locals(Node &program, Compilation &compilation)
{
    check_calls(program, compilation);
    check_returns(program, compilation);
    lay_out_frames(compilation);
    make_addresses_absolute(program, compilation);
}

void check_memory(const Compilation &compilation)
{
    unsigned size = compilation.target.variables_size;
    unsigned used =
      compilation.locals_start + compilation.locals_size + compilation.most_temporaries_used;
    if (compilation.locals_size == 0 || used <= size)
        return;
    const Frame *largest = &compilation.frames.front();
    for (const Frame &frame : compilation.frames)
        if (frame.base + frame.size > largest->base + largest->size)
            largest = &frame;
    fail(largest->largest_at,
         "Not enough variable memory for the locals: " + std::to_string(compilation.locals_start) +
           " words of globals, " + std::to_string(compilation.locals_size) + " of locals and " +
           std::to_string(compilation.most_temporaries_used) + " of scratch, the target has " +
           std::to_string(size) + " (use fewer or smaller locals)");
}

} // namespace aseba
