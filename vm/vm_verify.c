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
// active): for every few words, the first instruction at or after them and
// the depth there. A target is then checked by walking from its anchor, a
// few instructions at most.

#include "vm_internal.h"
#include "vm_opcodes.h"

#include <stddef.h>

// An opcode's shape: its words (bits 0-1), the stack words it pops (bits
// 2-3; a native's own count for NATIVE_CALL) and pushes (bit 4), whether
// execution may go on to the next instruction, whether it leads elsewhere
// (a jump, branch or call) and whether the stack must be empty after its
// pops (a jump, branch or return).
#define SHAPE_WORDS_MASK         0x03u
#define SHAPE_POPS_SHIFT         2
#define SHAPE_POPS_MASK          0x03u
#define SHAPE_PUSHES_SHIFT       4
#define SHAPE_GOES_ON            0x20u
#define SHAPE_HAS_TARGET         0x40u
#define SHAPE_LEAVES_EMPTY       0x80u
#define VM_POPS(pops, pushes)    pops
#define VM_PUSHES(pops, pushes)  pushes
#define IS_ONE_OF(code, a, b, c) ((code) == (a) || (code) == (b) || (code) == (c))
#define SHAPE_FLAGS(code)                                                                          \
    ((IS_ONE_OF(code, VM_OP_STOP, VM_OP_JUMP, VM_OP_SUB_RET) ? 0 : SHAPE_GOES_ON) |                \
     (IS_ONE_OF(code, VM_OP_JUMP, VM_OP_CONDITIONAL_BRANCH, VM_OP_SUB_CALL) ? SHAPE_HAS_TARGET     \
                                                                            : 0) |                 \
     (IS_ONE_OF(code, VM_OP_JUMP, VM_OP_CONDITIONAL_BRANCH, VM_OP_SUB_RET) ? SHAPE_LEAVES_EMPTY    \
                                                                           : 0))

static const uint8_t opcode_shapes[16] = {
#define VM_OPCODE_SHAPE(name, code, words, stack, meaning)                                         \
    [code] = (uint8_t)((words) | (VM_POPS stack) << SHAPE_POPS_SHIFT |                             \
                       (VM_PUSHES stack) << SHAPE_PUSHES_SHIFT | SHAPE_FLAGS(code)),
    VM_OPCODE_LIST(VM_OPCODE_SHAPE)
#undef VM_OPCODE_SHAPE
      [VM_OP_INVALID] = 1,
};

typedef struct verifier {
    vm_state *vm;
    uint16_t *bytecode;
    uint16_t size;
    uint16_t code_start; // right after the event table
    uint16_t code_end;   // after the last instruction anything can reach
    uint16_t *anchors;   // in the stack memory: pairs of pc and depth
    uint16_t anchor_count;
    uint16_t anchor_spacing; // words between anchored positions
} verifier;

static uint16_t opcode_of(uint16_t word)
{
    return word >> VM_OPCODE_SHIFT;
}

// Stack words the instruction starting with `word` pops.
static uint16_t pops_of(const vm_state *vm, uint16_t word)
{
    const vm_native *native;

    if (opcode_of(word) == VM_OP_NATIVE_CALL) {
        native = vm_native_at(&vm->natives, word & VM_OPERAND_MASK);
        if (native != NULL)
            return vm_native_stack_words(native);
    }
    return opcode_shapes[opcode_of(word)] >> SHAPE_POPS_SHIFT & SHAPE_POPS_MASK;
}

// Moves the walk past the instruction at *pc: *depth becomes what the next
// instruction sees. The instruction lies inside the bytecode.
static void step(const verifier *v, uint16_t *pc, uint16_t *depth)
{
    uint16_t word = v->bytecode[*pc];
    uint8_t shape = opcode_shapes[opcode_of(word)];

    if (shape & SHAPE_GOES_ON)
        *depth = (uint16_t)(*depth - pops_of(v->vm, word) + (shape >> SHAPE_PUSHES_SHIFT & 1));
    else
        *depth = 0;
    *pc = (uint16_t)(*pc + (shape & SHAPE_WORDS_MASK));
}

// Whether the instruction starting with `word` has `flag` in its shape.
static bool has_shape(uint16_t word, uint8_t flag)
{
    return (opcode_shapes[opcode_of(word)] & flag) != 0;
}

// Where the jump, branch or call at pc, whole inside the bytecode, leads;
// 0 for other instructions.
static uint16_t target_of(const uint16_t *bytecode, uint16_t pc)
{
    uint16_t word = bytecode[pc];

    switch (opcode_of(word)) {
    case VM_OP_JUMP: return (uint16_t)(pc + ((int16_t)(uint16_t)(word << 4) >> 4));
    case VM_OP_CONDITIONAL_BRANCH: return (uint16_t)(pc + bytecode[pc + 1]);
    case VM_OP_SUB_CALL: return word & VM_OPERAND_MASK; // an absolute address
    default: return 0;
    }
}

// Whether `count` words from `address` lie inside the variables.
static bool inside_variables(const vm_state *vm, uint16_t address, uint16_t count)
{
    return address <= vm->memory.variables_size && count <= vm->memory.variables_size - address;
}

// What is wrong with the instruction at pc, run with `depth` words on the
// stack, or NULL.
static const char *fault_at(const verifier *v, uint16_t pc, uint16_t depth)
{
    const vm_state *vm = v->vm;
    const uint16_t *bytecode = v->bytecode;
    uint16_t word = bytecode[pc];
    uint16_t opcode = opcode_of(word);
    uint16_t operand = word & VM_OPERAND_MASK;
    uint16_t operator_code = word & VM_OPERATOR_MASK;
    uint16_t pops = pops_of(vm, word);

    if ((uint16_t)(v->size - pc) < (opcode_shapes[opcode] & SHAPE_WORDS_MASK))
        return vm_error_bytecode_bounds;
    switch (opcode) {
    case VM_OP_LOAD:
    case VM_OP_STORE:
        if (operand >= vm->memory.variables_size)
            return vm_error_variables_bounds;
        break;
    case VM_OP_LOAD_INDIRECT:
    case VM_OP_STORE_INDIRECT:
        // The array, word 1 long: an index below its size is then inside.
        if (!inside_variables(vm, operand, bytecode[pc + 1]))
            return vm_error_variables_bounds;
        break;
    case VM_OP_UNARY_ARITHMETIC:
        if (operator_code >= VM_UNARY_NOT)
            return vm_error_unknown_operator;
        break;
    case VM_OP_BINARY_ARITHMETIC:
    case VM_OP_CONDITIONAL_BRANCH:
        if (operator_code >= VM_BINARY_OPERATOR_COUNT)
            return vm_error_unknown_operator;
        break;
    case VM_OP_EMIT:
        if (bytecode[pc + 2] > VM_MAX_EVENT_WORDS)
            return vm_error_event_too_large;
        if (!inside_variables(vm, bytecode[pc + 1], bytecode[pc + 2]))
            return vm_error_variables_bounds;
        break;
    case VM_OP_NATIVE_CALL:
        if (vm_native_at(&vm->natives, operand) == NULL || pops > VM_MAX_NATIVE_ARGUMENTS)
            return vm_error_unknown_native;
        break;
    case VM_OP_INVALID: return vm_error_unknown_bytecode;
    default: break;
    }
    if (depth < pops)
        return vm_error_stack_underflow;
    // Jumps, branches and returns leave with an empty stack (calls need not:
    // the callee's stack starts above the return address).
    if (has_shape(word, SHAPE_LEAVES_EMPTY) && depth != pops)
        return vm_error_invalid_jump;
    if (target_of(bytecode, pc) >= v->size)
        return vm_error_bytecode_bounds;
    return NULL;
}

static bool reject(vm_state *vm, uint16_t pc, const char *error)
{
    vm->rejection = error;
    vm->rejection_pc = pc;
    return false;
}

// Pass 1: checks every instruction of the code, finds where the code ends
// (`reach`: after the furthest place an entry, jump or call leads to so far),
// writes the anchors and clears the was-true bits.
static bool walk_code(verifier *v, uint16_t reach)
{
    uint16_t pc = v->code_start;
    uint16_t depth = 0;
    uint16_t next_anchor = 0;
    // Where the next anchored block starts. On the largest memories it may
    // wrap around 16 bits: anchors are then taken early, which is still
    // before their blocks (only further from them).
    uint16_t next_anchor_start = 0;
    bool goes_on = false;

    while (pc < reach || goes_on) {
        uint16_t word;
        uint16_t target;
        const char *fault;

        if (pc >= v->size) // the last instruction goes on past the end
            return reject(v->vm, v->code_end, vm_error_bytecode_bounds);
        while (next_anchor < v->anchor_count && next_anchor_start <= pc) {
            v->anchors[2 * next_anchor] = pc;
            v->anchors[2 * next_anchor + 1] = depth;
            next_anchor++;
            next_anchor_start = (uint16_t)(next_anchor_start + v->anchor_spacing);
        }
        fault = fault_at(v, pc, depth);
        if (fault != NULL)
            return reject(v->vm, pc, fault);
        word = v->bytecode[pc];
        target = target_of(v->bytecode, pc);
        if (target >= reach)
            reach = (uint16_t)(target + 1);
        if (opcode_of(word) == VM_OP_CONDITIONAL_BRANCH) // `when` starts false (§5.1)
            v->bytecode[pc] = (uint16_t)(word & ~VM_BRANCH_WAS_TRUE_BIT);
        goes_on = has_shape(word, SHAPE_GOES_ON);
        v->code_end = pc; // the last instruction, until the loop ends
        step(v, &pc, &depth);
    }
    v->code_end = pc;
    // Blocks after the last instruction start hold no target: their anchor
    // is the code's start, before any target.
    for (; next_anchor < v->anchor_count; next_anchor++) {
        v->anchors[2 * next_anchor] = v->code_start;
        v->anchors[2 * next_anchor + 1] = 0;
    }
    return true;
}

// Whether `target` is the start of an instruction of the code where the
// stack is empty, walking from the anchor of its block (which is at or
// before it, or after it when it is not an instruction start).
static bool is_empty_start(const verifier *v, uint16_t target)
{
    uint16_t pc = v->code_start;
    uint16_t depth = 0;

    if (target < v->code_start || target >= v->code_end)
        return false;
    if (v->anchor_count > 0) {
        uint16_t anchor = (uint16_t)(target / v->anchor_spacing);

        pc = v->anchors[2 * anchor];
        depth = v->anchors[2 * anchor + 1];
    }
    while (pc < target)
        step(v, &pc, &depth);
    return pc == target && depth == 0;
}

// Pass 2: the target of every jump, branch and call of the code, and every
// event address.
static bool check_targets(const verifier *v, uint16_t table_size)
{
    uint16_t pc = v->code_start;
    uint16_t depth = 0;
    uint16_t i;

    while (pc < v->code_end) {
        if (has_shape(v->bytecode[pc], SHAPE_HAS_TARGET) &&
            !is_empty_start(v, target_of(v->bytecode, pc)))
            return reject(v->vm, pc, vm_error_invalid_jump);
        step(v, &pc, &depth);
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
        if (address >= reach)
            reach = (uint16_t)(address + 1);
    }
    v.code_start = table_size;
    v.code_end = table_size;
    v.anchors = (uint16_t *)vm->memory.stack;
    v.anchor_count = vm->memory.stack_size / 2;
    // Every word below `size` has an anchor: spacing = size / count rounded
    // up, so count * spacing >= size.
    v.anchor_spacing = v.anchor_count > 0 ? (uint16_t)((v.size - 1u) / v.anchor_count + 1u) : 0;
    if (walk_code(&v, reach))
        check_targets(&v, table_size);
}
