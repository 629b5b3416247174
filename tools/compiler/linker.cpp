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

const char *const STACK_OVERFLOW_MESSAGE =
  "Execution stack will overflow, check for any recursive subroutine call and cut long "
  "mathematical expressions";

int opcode_of(const Instruction &instruction)
{
    return instruction.words[0] >> VM_OPCODE_SHIFT;
}

} // namespace

void check_stack(const std::vector<Section> &sections, const Compilation &compilation)
{
    unsigned stack_size = compilation.target.stack_size;
    size_t count = compilation.subroutines.size();
    std::vector<const Section *> subroutine(count, nullptr);
    std::vector<unsigned> call_depth(count, 0);
    for (const auto &section : sections) {
        if (section.is_subroutine) {
            subroutine[section.subroutine] = &section;
            continue;
        }
        if (section.stack_depth > stack_size)
            throw CompileFailure(STACK_OVERFLOW_MESSAGE);
        for (unsigned called : section.called)
            call_depth[called] = std::max(call_depth[called], 1u);
    }
    // raise call depths along calls until stable; recursion overflows
    bool changed = true;
    while (changed) {
        changed = false;
        for (size_t s = 0; s < count; ++s) {
            if (subroutine[s] == nullptr)
                continue;
            if (call_depth[s] + subroutine[s]->stack_depth > stack_size)
                throw CompileFailure(STACK_OVERFLOW_MESSAGE);
            for (unsigned called : subroutine[s]->called) {
                if (call_depth[called] < call_depth[s] + 1) {
                    call_depth[called] = call_depth[s] + 1;
                    changed = true;
                }
            }
        }
    }
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
                code.push_back({ { static_cast<uint16_t>(VM_OP_SUB_RET << VM_OPCODE_SHIFT) },
                                 section.last_line,
                                 -1 });
            subroutines[section.subroutine] = &section;
        } else if (!section.code.empty()) {
            section.code.push_back(
              { { static_cast<uint16_t>(VM_OP_STOP) }, section.last_line, -1 });
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
            address += static_cast<unsigned>(instruction.words.size());
    }
    for (size_t s = 0; s < subroutines.size(); ++s) {
        if (subroutines[s] == nullptr)
            continue;
        subroutine_address[s] = address;
        order.push_back(subroutines[s]);
        for (const auto &instruction : subroutines[s]->code)
            address += static_cast<unsigned>(instruction.words.size());
    }
    if (address > compilation.target.bytecode_size)
        throw CompileFailure("Script too big for target bytecode size");

    result.bytecode = table;
    result.line_of_word.assign(table.size(), 0);
    for (const Section *section : order) {
        for (const auto &instruction : section->code) {
            std::vector<uint16_t> words = instruction.words;
            if (instruction.subroutine >= 0)
                words[0] = static_cast<uint16_t>(
                  (VM_OP_SUB_CALL << VM_OPCODE_SHIFT) |
                  (subroutine_address[static_cast<size_t>(instruction.subroutine)] &
                   VM_OPERAND_MASK));
            for (uint16_t word : words) {
                result.bytecode.push_back(word);
                result.line_of_word.push_back(instruction.line);
            }
        }
    }
}

} // namespace aseba
