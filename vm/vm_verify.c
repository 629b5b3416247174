// The load-time verifier, in the spirit of eBPF's: it runs whenever the
// bytecode changes (vm_reset, so after every SET_BYTECODE chunk) and proves
// once what the run loop would otherwise check at every instruction:
//   - every instruction lies whole inside the bytecode, with a known opcode,
//     operator and native, and execution cannot run past the end of the code;
//   - every LOAD and STORE address, every LOAD_INDIRECT/STORE_INDIRECT array
//     and every EMIT area lies inside the variables, and an emitted event
//     fits a message;
//   - every jump, branch, call and event address lands on the start of an
//     instruction, with the stack empty there, and jumps, branches and
//     returns leave with an empty stack: no instruction pops a value that the
//     same event or subroutine did not push.
// What depends on run-time values stays in the loop (vm.c): an indirect index
// against its array's size, division by zero, stack overflow (the depth grows
// with the chain of subroutine calls) and a SUB_RET outside any call.
//
// The walk is linear, from the end of the event table to the last
// instruction that an event, a jump or a call can reach ("the code"); words
// after it (an older, longer program) are never run and not looked at. The
// depth is counted from the last point where the stack is empty, in the
// current event or subroutine: after an instruction that does not go on to
// the next one (STOP, JUMP, SUB_RET), the next can only be reached by a jump,
// so it starts empty.
//
// Checking a jump needs the depth at its target, but a table with an entry
// per word is more RAM than the e-puck can spare. While the first walk goes,
// it writes anchors into the VM's stack memory (idle while no event is
// active): for every few words, the last instruction start before them where
// the stack is empty. A target is then checked by walking from its anchor.

#include "vm_internal.h"
#include "vm_opcodes.h"

#include <stddef.h>

// The two halves of the opcode list's (pops, pushes) column.
#define VM_POPS(pops, pushes)   pops
#define VM_PUSHES(pops, pushes) pushes

// What the walk needs to know of one instruction.
typedef struct instruction {
    uint16_t word;
    uint16_t opcode;
    uint16_t length; // words
    uint16_t pops;   // stack words it needs
    uint16_t pushes;
    bool goes_on;           // whether the next instruction may follow it
    bool jumps;             // JUMP, CONDITIONAL_BRANCH or SUB_CALL: `target` is set
    bool needs_empty_stack; // the stack must be empty after its pops
    uint16_t target;
} instruction;

typedef struct verifier {
    vm_state *vm;
    const uint16_t *bytecode;
    uint16_t size;
    uint16_t code_start; // right after the event table
    uint16_t code_end;   // after the last instruction anything can reach
    uint16_t *anchors;   // in the stack memory
    uint16_t anchor_count;
    uint16_t anchor_spacing; // words between anchored positions
} verifier;

// The instruction at pc, whose first word lies inside the bytecode. Operand
// words are read only once the caller knows they are inside too.
static instruction decode(const verifier *v, uint16_t pc)
{
    instruction ins;
    uint16_t word = v->bytecode[pc];

    ins.word = word;
    ins.opcode = word >> VM_OPCODE_SHIFT;
    ins.length = vm_instruction_words(word);
    ins.jumps = false;
    ins.needs_empty_stack = false;
    ins.target = 0;
    switch (ins.opcode) {
#define VM_OPCODE_EFFECTS(name, code, words, stack, meaning)                                       \
    case code:                                                                                     \
        ins.pops = VM_POPS stack;                                                                  \
        ins.pushes = VM_PUSHES stack;                                                              \
        break;
        VM_OPCODE_LIST(VM_OPCODE_EFFECTS)
#undef VM_OPCODE_EFFECTS
    default: ins.pops = ins.pushes = 0; break;
    }
    ins.goes_on = ins.opcode != VM_OP_STOP && ins.opcode != VM_OP_JUMP &&
                  ins.opcode != VM_OP_SUB_RET && ins.opcode != VM_OP_INVALID;
    if (ins.opcode == VM_OP_JUMP) {
        // Sign-extend the 12-bit displacement.
        ins.target = (uint16_t)(pc + ((int16_t)(uint16_t)(word << 4) >> 4));
        ins.jumps = ins.needs_empty_stack = true;
    } else if (ins.opcode == VM_OP_CONDITIONAL_BRANCH && v->size - pc >= 2) {
        ins.target = (uint16_t)(pc + v->bytecode[pc + 1]);
        ins.jumps = ins.needs_empty_stack = true;
    } else if (ins.opcode == VM_OP_SUB_CALL) {
        // The callee's frame starts empty, above the return address.
        ins.target = word & VM_OPERAND_MASK;
        ins.jumps = true;
    } else if (ins.opcode == VM_OP_SUB_RET) {
        ins.needs_empty_stack = true;
    } else if (ins.opcode == VM_OP_NATIVE_CALL && (word & VM_OPERAND_MASK) < v->vm->natives.count) {
        ins.pops = v->vm->natives.natives[word & VM_OPERAND_MASK]->stack_words;
    }
    return ins;
}

// The depth after `ins`, run at `depth`, as the next instruction sees it.
static uint16_t depth_after(const instruction *ins, uint16_t depth)
{
    return ins->goes_on ? (uint16_t)(depth - ins->pops + ins->pushes) : 0;
}

static bool reject(vm_state *vm, uint16_t pc, const char *error)
{
    vm->rejection = error;
    vm->rejection_pc = pc;
    return false;
}

// Whether `count` words from `address` lie inside the variables.
static bool inside_variables(const vm_state *vm, uint16_t address, uint16_t count)
{
    return address <= vm->memory.variables_size && count <= vm->memory.variables_size - address;
}

// The checks of one instruction at pc, run with `depth` words on the stack.
static bool check(const verifier *v, uint16_t pc, uint16_t depth, const instruction *ins)
{
    vm_state *vm = v->vm;
    uint16_t operand = ins->word & VM_OPERAND_MASK;
    uint16_t operator_code = ins->word & VM_OPERATOR_MASK;

    if ((uint16_t)(v->size - pc) < ins->length)
        return reject(vm, pc, vm_error_bytecode_bounds);
    switch (ins->opcode) {
    case VM_OP_LOAD:
    case VM_OP_STORE:
        if (operand >= vm->memory.variables_size)
            return reject(vm, pc, vm_error_variables_bounds);
        break;
    case VM_OP_LOAD_INDIRECT:
    case VM_OP_STORE_INDIRECT:
        // The array, word 1 long: an index below its size is then inside.
        if (!inside_variables(vm, operand, v->bytecode[pc + 1]))
            return reject(vm, pc, vm_error_variables_bounds);
        break;
    case VM_OP_UNARY_ARITHMETIC:
        if (operator_code >= VM_UNARY_NOT)
            return reject(vm, pc, vm_error_unknown_operator);
        break;
    case VM_OP_BINARY_ARITHMETIC:
    case VM_OP_CONDITIONAL_BRANCH:
        if (operator_code >= VM_BINARY_OPERATOR_COUNT)
            return reject(vm, pc, vm_error_unknown_operator);
        break;
    case VM_OP_EMIT:
        if (v->bytecode[pc + 2] > VM_MAX_EVENT_WORDS)
            return reject(vm, pc, vm_error_event_too_large);
        if (!inside_variables(vm, v->bytecode[pc + 1], v->bytecode[pc + 2]))
            return reject(vm, pc, vm_error_variables_bounds);
        break;
    case VM_OP_NATIVE_CALL:
        if (operand >= vm->natives.count || ins->pops > VM_MAX_NATIVE_ARGUMENTS)
            return reject(vm, pc, vm_error_unknown_native);
        break;
    case VM_OP_INVALID: return reject(vm, pc, vm_error_unknown_bytecode);
    default: break;
    }
    if (depth < ins->pops)
        return reject(vm, pc, vm_error_stack_underflow);
    if (ins->needs_empty_stack && depth != ins->pops)
        return reject(vm, pc, vm_error_invalid_jump);
    if (ins->jumps && ins->target >= v->size)
        return reject(vm, pc, vm_error_bytecode_bounds);
    return true;
}

// Pass 1: checks every instruction of the code, finds where the code ends,
// writes the anchors and clears the was-true bits.
static bool walk_code(verifier *v, uint16_t reach)
{
    uint16_t *bytecode = v->vm->memory.bytecode;
    uint16_t pc = v->code_start;
    uint16_t depth = 0;
    uint16_t last_empty = pc;
    uint16_t next_anchor = 0;
    uint32_t next_anchor_start = 0;
    bool goes_on = false;

    while (pc < reach || goes_on) {
        instruction ins;

        if (pc >= v->size) // the last instruction goes on past the end
            return reject(v->vm, v->code_end, vm_error_bytecode_bounds);
        if (depth == 0)
            last_empty = pc;
        while (next_anchor < v->anchor_count && next_anchor_start <= pc) {
            v->anchors[next_anchor++] = last_empty;
            next_anchor_start += v->anchor_spacing;
        }
        ins = decode(v, pc);
        if (!check(v, pc, depth, &ins))
            return false;
        if (ins.jumps && ins.target >= reach)
            reach = (uint16_t)(ins.target + 1);
        if (ins.opcode == VM_OP_CONDITIONAL_BRANCH) // `when` starts as false (bytecode.md §5.1)
            bytecode[pc] &= (uint16_t)~VM_BRANCH_WAS_TRUE_BIT;
        depth = depth_after(&ins, depth);
        goes_on = ins.goes_on;
        v->code_end = pc; // the last instruction, until the loop ends
        pc = (uint16_t)(pc + ins.length);
    }
    v->code_end = pc;
    while (next_anchor < v->anchor_count)
        v->anchors[next_anchor++] = last_empty;
    return true;
}

// Whether `target` is the start of an instruction of the code where the
// stack is empty, walking from the anchor before it.
static bool is_empty_start(const verifier *v, uint16_t target)
{
    uint16_t pc = v->code_start;
    uint16_t depth = 0;

    if (target < v->code_start || target >= v->code_end)
        return false;
    if (v->anchor_count > 0)
        pc = v->anchors[target / v->anchor_spacing];
    while (pc < target) {
        instruction ins = decode(v, pc);

        depth = depth_after(&ins, depth);
        pc = (uint16_t)(pc + ins.length);
    }
    return pc == target && depth == 0;
}

// Pass 2: every target of the code, and every event address.
static bool check_targets(const verifier *v, uint16_t table_size)
{
    uint16_t pc;
    uint16_t i;

    for (pc = v->code_start; pc < v->code_end;) {
        instruction ins = decode(v, pc);

        if (ins.jumps && !is_empty_start(v, ins.target))
            return reject(v->vm, pc, vm_error_invalid_jump);
        pc = (uint16_t)(pc + ins.length);
    }
    for (i = 1; i < table_size && i + 1 < v->size; i += 2) {
        uint16_t address = v->bytecode[i + 1];

        if (address != 0 && !is_empty_start(v, address))
            return reject(v->vm, (uint16_t)(i + 1), vm_error_invalid_jump);
    }
    return true;
}

void vm_verify(vm_state *vm)
{
    verifier v;
    uint16_t table_size;
    uint16_t reach = 0;
    uint16_t i;

    vm->rejection = NULL;
    vm->rejection_pc = 0;
    if (vm->memory.bytecode_size == 0)
        return;
    v.vm = vm;
    v.bytecode = vm->memory.bytecode;
    v.size = vm->memory.bytecode_size;
    table_size = v.bytecode[0];
    if (table_size > v.size) {
        reject(vm, 0, vm_error_bytecode_bounds);
        return;
    }
    // The entries vm_event_address reads; 0 means "not handled".
    for (i = 1; i < table_size && i + 1 < v.size; i += 2) {
        uint16_t address = v.bytecode[i + 1];

        if (address >= v.size) {
            reject(vm, (uint16_t)(i + 1), vm_error_bytecode_bounds);
            return;
        }
        if (address != 0 && address >= reach)
            reach = (uint16_t)(address + 1);
    }
    v.code_start = table_size;
    v.code_end = table_size;
    v.anchors = (uint16_t *)vm->memory.stack;
    v.anchor_count = vm->memory.stack_size;
    // Every word below `size` has an anchor: count * spacing >= size.
    v.anchor_spacing =
      v.anchor_count > 0 ? (uint16_t)(((uint32_t)v.size + v.anchor_count - 1) / v.anchor_count) : 0;
    if (walk_code(&v, reach))
        check_targets(&v, table_size);
}
