// The stack-depth check (language.md §11.3) and the bytecode layout (§10):
// event table sorted by id, handlers in that order, then subroutines in
// definition order with their calls patched.

#include <algorithm>
#include <map>

#include "codegen.hpp"
#include "diagnostics.hpp"
#include "vm_opcodes.h"

namespace aseba
{

namespace
{

int opcode_of(const Instruction &instruction)
{
    return instruction.words[0] >> VM_OPCODE_SHIFT;
}

// The stack each section needs, its calls included (language.md §11.3: a
// call needs the words under it, the return address and what the called
// subroutine needs). Equivalent to the reference's call-depth rule for
// programs whose calls are all `callsub` statements.
class StackCheck
{
  public:
    StackCheck(const std::vector<Section> &all_sections, const Compilation &state)
      : sections(all_sections)
      , compilation(state)
      , section_of(state.subroutines.size(), 0)
      , progress(all_sections.size(), Progress::NotVisited)
      , need(all_sections.size(), 0)
    {
        for (size_t i = 0; i < sections.size(); ++i)
            if (sections[i].is_subroutine)
                section_of[sections[i].subroutine] = i;
    }

    // Subroutines first, so that an overflow is reported where it starts.
    void run()
    {
        for (size_t i = 0; i < sections.size(); ++i)
            if (sections[i].is_subroutine)
                visit(i);
        for (size_t i = 0; i < sections.size(); ++i)
            visit(i);
    }

  private:
    enum class Progress { NotVisited, InProgress, Done };

    // A section being followed: the next of its calls to look at.
    struct Visit {
        size_t section;
        size_t next_call = 0;
        unsigned deepest = 0;
    };

    const std::vector<Section> &sections;
    const Compilation &compilation;
    std::vector<size_t> section_of; // subroutine index -> section
    std::vector<Progress> progress;
    std::vector<unsigned> need;

    const std::string &name_of(size_t section) const
    {
        return compilation.subroutines[sections[section].subroutine];
    }

    // Depth first along the calls, with a stack of our own (call chains may
    // be as long as the program): a section met again before it is done is
    // a cycle.
    void visit(size_t root)
    {
        if (progress[root] != Progress::NotVisited)
            return;
        unsigned stack_size = compilation.target.stack_size;
        std::vector<Visit> path{ { root, 0, sections[root].stack_depth } };
        progress[root] = Progress::InProgress;
        while (!path.empty()) {
            Visit &top = path.back();
            const Section &section = sections[top.section];
            if (top.next_call == section.calls.size()) {
                if (section.stack_depth > stack_size)
                    fail(section.deepest_at,
                         "Execution stack will overflow: this statement needs " +
                           std::to_string(section.stack_depth) +
                           " words of stack, the target has " + std::to_string(stack_size) +
                           ": cut long mathematical expressions");
                need[top.section] = top.deepest;
                progress[top.section] = Progress::Done;
                path.pop_back();
                continue;
            }
            const StackCall &call = section.calls[top.next_call];
            size_t called = section_of[call.subroutine];
            if (progress[called] == Progress::InProgress)
                fail_recursion(path, called, call);
            if (progress[called] == Progress::NotVisited) {
                progress[called] = Progress::InProgress;
                path.push_back({ called, 0, sections[called].stack_depth });
                continue; // this call is looked at again once `called` is done
            }
            unsigned call_need = call.words_below + 1 + need[called];
            if (call_need > stack_size)
                fail(call.position,
                     "Execution stack will overflow: this call of " + name_of(called) + " needs " +
                       std::to_string(call_need) + " words of stack (" +
                       std::to_string(call.words_below) +
                       " for the values under it, 1 for the return address, " +
                       std::to_string(need[called]) + " for " + name_of(called) +
                       "), the target has " + std::to_string(stack_size) +
                       ": make the expression around it or the subroutine simpler");
            top.deepest = std::max(top.deepest, call_need);
            ++top.next_call;
        }
    }

    // `called` is on the path already: the calls from it to `closing` form
    // the cycle.
    [[noreturn]] void fail_recursion(const std::vector<Visit> &path,
                                     size_t called,
                                     const StackCall &closing) const
    {
        std::string cycle = "sub " + name_of(called);
        bool in_cycle = false;
        bool first = true;
        for (size_t i = 0; i + 1 < path.size(); ++i) {
            in_cycle = in_cycle || path[i].section == called;
            if (!in_cycle)
                continue;
            cycle += (first ? " calls sub " : ", which calls sub ") + name_of(path[i + 1].section);
            first = false;
        }
        cycle += first ? " calls itself" : ", which calls sub " + name_of(called);
        fail(closing.position,
             "Recursion is not allowed: " + cycle +
               " (a subroutine must not call itself, directly or through others)");
    }
};

} // namespace

void check_stack(const std::vector<Section> &sections, const Compilation &compilation)
{
    StackCheck(sections, compilation).run();
}

void link(std::vector<Section> sections, const Compilation &compilation, CompileResult &result)
{
    std::map<unsigned, Section *> events; // sorted by id
    std::vector<Section *> subroutines(compilation.subroutines.size(), nullptr);
    for (auto &section : sections) {
        if (section.is_subroutine) {
            Code &code = section.code;
            for (auto &instruction : code)
                if (opcode_of(instruction) == VM_OP_STOP)
                    instruction.words[0] = static_cast<uint16_t>(VM_OP_SUB_RET << VM_OPCODE_SHIFT);
            if (code.empty() || opcode_of(code.back()) != VM_OP_SUB_RET)
                code.push_back(make_instruction(
                  { static_cast<uint16_t>(VM_OP_SUB_RET << VM_OPCODE_SHIFT) }, section.last_line));
            subroutines[section.subroutine] = &section;
        } else if (!section.code.empty()) {
            section.code.push_back(
              make_instruction({ static_cast<uint16_t>(VM_OP_STOP) }, section.last_line));
            events[section.event_id] = &section;
        }
    }
    auto table_size = static_cast<unsigned>(2 * events.size() + 1);
    unsigned address = table_size;
    std::vector<unsigned> subroutine_address(subroutines.size(), 0);
    std::vector<uint16_t> table{ static_cast<uint16_t>(table_size) };
    std::vector<const Section *> order;
    for (const auto &[id, section] : events) {
        table.push_back(static_cast<uint16_t>(id));
        table.push_back(static_cast<uint16_t>(address));
        order.push_back(section);
        for (const auto &instruction : section->code)
            address += instruction.word_count;
    }
    for (size_t s = 0; s < subroutines.size(); ++s) {
        if (subroutines[s] == nullptr)
            continue;
        subroutine_address[s] = address;
        order.push_back(subroutines[s]);
        for (const auto &instruction : subroutines[s]->code)
            address += instruction.word_count;
    }
    if (address > compilation.target.bytecode_size) {
        // the first handler or subroutine that ends beyond the limit
        if (order.empty())
            throw CompileFailure("Script too big for target bytecode size");
        unsigned end = table_size;
        const Section *first_out = order.front();
        for (const Section *section : order) {
            for (const auto &instruction : section->code)
                end += instruction.word_count;
            first_out = section;
            if (end > compilation.target.bytecode_size)
                break;
        }
        fail(first_out->start,
             "Script too big for target bytecode size: the program needs " +
               std::to_string(address) + " words, the target has " +
               std::to_string(compilation.target.bytecode_size) +
               "; the code from this handler or subroutine on does not fit");
    }

    result.bytecode = table;
    result.bytecode.reserve(address);
    result.line_of_word.assign(table.size(), 0);
    result.line_of_word.reserve(address);
    for (const Section *section : order) {
        for (const auto &instruction : section->code) {
            std::array<uint16_t, MAX_INSTRUCTION_WORDS> words = instruction.words;
            if (instruction.subroutine >= 0)
                words[0] = static_cast<uint16_t>(
                  (VM_OP_SUB_CALL << VM_OPCODE_SHIFT) |
                  (subroutine_address[static_cast<size_t>(instruction.subroutine)] &
                   VM_OPERAND_MASK));
            for (unsigned k = 0; k < instruction.word_count; ++k) {
                result.bytecode.push_back(words[k]);
                result.line_of_word.push_back(instruction.line);
            }
        }
    }
}

} // namespace aseba
