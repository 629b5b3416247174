// The Aseba interpreter: event setup and the run loop (bytecode.md §2-§9).
//
// The loop keeps pc, sp and the memory bounds in locals and writes them back
// only where the outside world can look: at natives, emits, errors, the end
// of the event, breakpoints and when the step budget runs out. Every memory
// access is checked, so no bytecode can reach outside the caller's arrays.

#include "vm.h"
#include "vm_opcodes.h"

#include <stddef.h>

// Texts of the NODE_SPECIFIC_ERROR reports of bytecode.md §8.5.
static const char error_stack_overflow[] = "stack overflow";
static const char error_stack_underflow[] = "stack underflow";
static const char error_variables_bounds[] = "out of variables bounds";
static const char error_bytecode_bounds[] = "out of bytecode bounds";
static const char error_unknown_bytecode[] = "unknown bytecode";
static const char error_unknown_operator[] = "unknown operator";
static const char error_unknown_native[] = "unknown native function";
static const char error_event_too_large[] = "emitted event too large";

// How the run loop ended.
enum run_outcome { RUN_EVENT_ENDED, RUN_BUDGET_SPENT, RUN_BREAKPOINT, RUN_INTERRUPTED, RUN_ERROR };

void vm_init(vm_state *vm,
             const vm_memory *memory,
             uint16_t node_id,
             const vm_native_table *natives,
             const vm_callbacks *callbacks,
             void *context)
{
    uint16_t i;

    vm->node_id = node_id;
    vm->pc = 0;
    vm->sp = -1;
    vm->flags = 0;
    vm->breakpoint_count = 0;
    vm->random_state = 0;
    vm->memory = *memory;
    // sp is a signed 16-bit index: a larger stack could not be addressed.
    if (vm->memory.stack_size > INT16_MAX)
        vm->memory.stack_size = INT16_MAX;
    vm->natives = *natives;
    vm->callbacks = callbacks;
    vm->context = context;
    if (vm->memory.bytecode_size > 0)
        vm->memory.bytecode[0] = 0;
    for (i = 0; i < vm->memory.variables_size; i++)
        vm->memory.variables[i] = 0;
}

uint16_t vm_event_address(const vm_state *vm, uint16_t event)
{
    const uint16_t *bytecode = vm->memory.bytecode;
    uint16_t table_size;
    uint16_t i;

    if (vm->memory.bytecode_size == 0)
        return 0;
    table_size = bytecode[0];
    for (i = 1; i < table_size && i + 1 < vm->memory.bytecode_size; i += 2) {
        if (bytecode[i] == event)
            return bytecode[i + 1];
    }
    return 0;
}

uint16_t vm_setup_event(vm_state *vm, uint16_t event)
{
    uint16_t address = vm_event_address(vm, event);

    if (address == 0)
        return 0;
    if (vm->flags & VM_FLAG_EVENT_ACTIVE)
        vm->callbacks->event_killed(vm->context, vm->pc);
    vm->pc = address;
    vm->sp = -1;
    vm->flags |= VM_FLAG_EVENT_ACTIVE;
    if (vm->flags & VM_FLAG_STEP_BY_STEP)
        vm->callbacks->execution_state_changed(vm->context, vm->pc, vm->flags);
    return address;
}

// --- errors: each stops the VM and sends one report --------------------------

void vm_error_array_access(vm_state *vm, uint16_t size, uint16_t index)
{
    vm->flags = VM_FLAG_STEP_BY_STEP;
    vm->callbacks->array_access_out_of_bounds(vm->context, vm->pc, size, index);
}

void vm_error_division_by_zero(vm_state *vm)
{
    vm->flags = VM_FLAG_STEP_BY_STEP;
    vm->callbacks->division_by_zero(vm->context, vm->pc);
}

void vm_error_node_specific(vm_state *vm, const char *message)
{
    vm->flags = VM_FLAG_STEP_BY_STEP;
    vm->callbacks->node_specific_error(vm->context, vm->pc, message);
}

int16_t *vm_variables(vm_state *vm, uint16_t address, uint16_t length)
{
    // An empty span touches nothing: any address will do, as upstream.
    if (length == 0)
        return vm->memory.variables;
    if (address >= vm->memory.variables_size || length > vm->memory.variables_size - address) {
        vm_error_node_specific(vm, error_variables_bounds);
        return NULL;
    }
    return vm->memory.variables + address;
}

// --- arithmetic (bytecode.md §4) ---------------------------------------------

// Operands are promoted to 32 bits and results truncated to 16, as upstream
// does on 32-bit hosts; the casts through uint32_t keep every step defined C.
static inline int16_t truncate(int32_t value)
{
    return (int16_t)(uint16_t)(uint32_t)value;
}

// Returns false for an unknown operator; sets *division_by_zero (and gives 0)
// for a zero divisor.
static inline bool binary_operation(uint16_t operation,
                                    int16_t a,
                                    int16_t b,
                                    int16_t *result,
                                    bool *division_by_zero)
{
    int32_t x = a, y = b;

    switch (operation) {
    case VM_BINARY_SHIFT_LEFT: *result = truncate((int32_t)((uint32_t)x << (y & 31))); break;
    case VM_BINARY_SHIFT_RIGHT: *result = truncate(x >> (y & 31)); break;
    case VM_BINARY_ADD: *result = truncate(x + y); break;
    case VM_BINARY_SUB: *result = truncate(x - y); break;
    case VM_BINARY_MULT: *result = truncate(x * y); break;
    case VM_BINARY_DIV:
    case VM_BINARY_MOD:
        if (y == 0) {
            *division_by_zero = true;
            *result = 0;
        } else {
            *result = truncate(operation == VM_BINARY_DIV ? x / y : x % y);
        }
        break;
    case VM_BINARY_BIT_OR: *result = (int16_t)(a | b); break;
    case VM_BINARY_BIT_XOR: *result = (int16_t)(a ^ b); break;
    case VM_BINARY_BIT_AND: *result = (int16_t)(a & b); break;
    case VM_BINARY_EQUAL: *result = a == b; break;
    case VM_BINARY_NOT_EQUAL: *result = a != b; break;
    case VM_BINARY_BIGGER_THAN: *result = a > b; break;
    case VM_BINARY_BIGGER_EQUAL_THAN: *result = a >= b; break;
    case VM_BINARY_SMALLER_THAN: *result = a < b; break;
    case VM_BINARY_SMALLER_EQUAL_THAN: *result = a <= b; break;
    case VM_BINARY_OR: *result = a != 0 || b != 0; break;
    case VM_BINARY_AND: *result = a != 0 && b != 0; break;
    default: return false;
    }
    return true;
}

static bool at_breakpoint(const vm_state *vm, uint16_t pc)
{
    uint16_t i;

    for (i = 0; i < vm->breakpoint_count; i++) {
        if (vm->breakpoints[i] == pc)
            return true;
    }
    return false;
}

// --- the run loop ------------------------------------------------------------

// Fetch: the budget, the breakpoint branch (free when none are set: the count
// is a local that stays 0) and the bytecode bound, then the instruction word.
#define FETCH()                                                                                    \
    if (remaining == 0)                                                                            \
        goto budget_spent;                                                                         \
    remaining--;                                                                                   \
    if (breakpoint_count != 0 && at_breakpoint(vm, pc))                                            \
        goto breakpoint_hit;                                                                       \
    if (pc >= bytecode_size)                                                                       \
        goto bytecode_out_of_bounds;                                                               \
    word = bytecode[pc];

// The dispatch is written once and compiles as a switch (the reference) or,
// with VM_USE_COMPUTED_GOTO, as a jump through a table of labels.
#if VM_USE_COMPUTED_GOTO
#define VM_LOOP_BEGIN VM_NEXT();
#define VM_LOOP_END
#define VM_CASE(name) opcode_##name:
#define VM_NEXT()                                                                                  \
    do {                                                                                           \
        FETCH();                                                                                   \
        goto *dispatch_table[word >> VM_OPCODE_SHIFT];                                             \
    } while (0)
#else
#define VM_LOOP_BEGIN                                                                              \
    for (;;) {                                                                                     \
        FETCH();                                                                                   \
        switch (word >> VM_OPCODE_SHIFT) {
#define VM_LOOP_END                                                                                \
    }                                                                                              \
    }
#define VM_CASE(name) case VM_OP_##name:
#define VM_NEXT()     continue
#endif

// Stack guards: the stack must hold `n` more values, or have `n` values.
#define NEED_ROOM(n)                                                                               \
    if (sp + (n) > stack_top)                                                                      \
    goto stack_overflow
#define NEED_VALUES(n)                                                                             \
    if (sp < (n)-1)                                                                                \
    goto stack_underflow
// The instruction's operand words must lie inside the bytecode.
#define NEED_WORDS(n)                                                                              \
    if ((uint16_t)(bytecode_size - pc) < (n))                                                      \
    goto bytecode_out_of_bounds

// Runs at most `budget` instructions of the active event. A run (as opposed
// to a single step) stops at breakpoints and when EVENT_RUNNING is cleared.
static enum run_outcome execute(vm_state *vm, uint16_t budget, bool running)
{
    uint16_t *const bytecode = vm->memory.bytecode;
    int16_t *const variables = vm->memory.variables;
    int16_t *const stack = vm->memory.stack;
    const uint16_t bytecode_size = vm->memory.bytecode_size;
    const uint16_t variables_size = vm->memory.variables_size;
    const int16_t stack_top = (int16_t)(vm->memory.stack_size - 1);
    const uint16_t breakpoint_count = running ? vm->breakpoint_count : 0;
    uint16_t remaining = budget;
    uint16_t pc = vm->pc;
    int16_t sp = vm->sp;
    uint16_t word;
    uint16_t operand;
    int16_t result;
    bool division_by_zero;
    const char *error;

#if VM_USE_COMPUTED_GOTO
    static const void *const dispatch_table[16] = {
#define VM_OPCODE_LABEL(name, code, words, effect, meaning) [code] = &&opcode_##name,
        VM_OPCODE_LIST(VM_OPCODE_LABEL)
#undef VM_OPCODE_LABEL
          [VM_OP_INVALID] = &&opcode_INVALID,
    };
#endif

    VM_LOOP_BEGIN

    VM_CASE(STOP)
    {
        vm->flags &= (uint16_t)~VM_FLAG_EVENT_ACTIVE;
        vm->pc = pc;
        vm->sp = sp;
        return RUN_EVENT_ENDED;
    }

    VM_CASE(SMALL_IMMEDIATE)
    {
        NEED_ROOM(1);
        // Sign-extend the 12-bit operand.
        stack[++sp] = (int16_t)((uint16_t)(word << 4)) >> 4;
        pc++;
        VM_NEXT();
    }

    VM_CASE(LARGE_IMMEDIATE)
    {
        NEED_WORDS(2);
        NEED_ROOM(1);
        stack[++sp] = (int16_t)bytecode[pc + 1];
        pc += 2;
        VM_NEXT();
    }

    VM_CASE(LOAD)
    {
        operand = word & VM_OPERAND_MASK;
        if (operand >= variables_size)
            goto variables_out_of_bounds;
        NEED_ROOM(1);
        stack[++sp] = variables[operand];
        pc++;
        VM_NEXT();
    }

    VM_CASE(STORE)
    {
        operand = word & VM_OPERAND_MASK;
        if (operand >= variables_size)
            goto variables_out_of_bounds;
        NEED_VALUES(1);
        variables[operand] = stack[sp--];
        pc++;
        VM_NEXT();
    }

    VM_CASE(LOAD_INDIRECT)
    {
        uint16_t index, size;

        NEED_WORDS(2);
        NEED_VALUES(1);
        operand = word & VM_OPERAND_MASK;
        size = bytecode[pc + 1];
        index = (uint16_t)stack[sp];
        if (index >= size)
            goto array_out_of_bounds;
        if (operand >= variables_size || index >= variables_size - operand)
            goto variables_out_of_bounds;
        stack[sp] = variables[operand + index];
        pc += 2;
        VM_NEXT();
    }

    VM_CASE(STORE_INDIRECT)
    {
        uint16_t index, size;

        NEED_WORDS(2);
        NEED_VALUES(2);
        operand = word & VM_OPERAND_MASK;
        size = bytecode[pc + 1];
        index = (uint16_t)stack[sp];
        if (index >= size)
            goto array_out_of_bounds;
        if (operand >= variables_size || index >= variables_size - operand)
            goto variables_out_of_bounds;
        variables[operand + index] = stack[sp - 1];
        sp -= 2;
        pc += 2;
        VM_NEXT();
    }

    VM_CASE(UNARY_ARITHMETIC)
    {
        int32_t value;

        NEED_VALUES(1);
        value = stack[sp];
        switch (word & VM_OPERATOR_MASK) {
        case VM_UNARY_SUB: value = -value; break;
        case VM_UNARY_ABS: value = value < 0 ? -value : value; break;
        case VM_UNARY_BIT_NOT: value = ~value; break;
        default: goto unknown_operator;
        }
        stack[sp] = truncate(value);
        pc++;
        VM_NEXT();
    }

    VM_CASE(BINARY_ARITHMETIC)
    {
        NEED_VALUES(2);
        division_by_zero = false;
        if (!binary_operation(
              word & VM_OPERATOR_MASK, stack[sp - 1], stack[sp], &result, &division_by_zero))
            goto unknown_operator;
        stack[--sp] = result;
        if (division_by_zero) {
            // The instruction completes with 0 and pc moves on, then the VM stops.
            vm->pc = pc;
            vm->sp = sp;
            vm_error_division_by_zero(vm);
            vm->pc = (uint16_t)(pc + 1);
            return RUN_ERROR;
        }
        pc++;
        VM_NEXT();
    }

    VM_CASE(JUMP)
    {
        // Sign-extend the 12-bit displacement; the next fetch checks the target.
        pc = (uint16_t)(pc + ((int16_t)((uint16_t)(word << 4)) >> 4));
        VM_NEXT();
    }

    VM_CASE(CONDITIONAL_BRANCH)
    {
        uint16_t branch_pc = pc;
        bool is_true;

        NEED_WORDS(2);
        NEED_VALUES(2);
        division_by_zero = false;
        if (!binary_operation(
              word & VM_OPERATOR_MASK, stack[sp - 1], stack[sp], &result, &division_by_zero))
            goto unknown_operator;
        sp -= 2;
        is_true = result != 0;
        // A `when` takes its true path only on a false-to-true edge: the
        // instruction word itself remembers the last result.
        if (is_true && !((word & VM_BRANCH_IS_WHEN_BIT) && (word & VM_BRANCH_WAS_TRUE_BIT)))
            pc += 2;
        else
            pc = (uint16_t)(pc + (int16_t)bytecode[pc + 1]);
        if (is_true)
            bytecode[branch_pc] = word | VM_BRANCH_WAS_TRUE_BIT;
        else
            bytecode[branch_pc] = word & (uint16_t)~VM_BRANCH_WAS_TRUE_BIT;
        if (division_by_zero) {
            vm->pc = branch_pc;
            vm->sp = sp;
            vm_error_division_by_zero(vm);
            vm->pc = pc;
            return RUN_ERROR;
        }
        VM_NEXT();
    }

    VM_CASE(EMIT)
    {
        uint16_t address, count;

        NEED_WORDS(3);
        address = bytecode[pc + 1];
        count = bytecode[pc + 2];
        if (count > VM_MAX_EVENT_WORDS) {
            error = error_event_too_large;
            goto node_error;
        }
        if (address > variables_size || count > variables_size - address)
            goto variables_out_of_bounds;
        vm->pc = pc;
        vm->sp = sp;
        vm->callbacks->emit(vm->context, word & VM_OPERAND_MASK, variables + address, count);
        pc += 3;
        VM_NEXT();
    }

    VM_CASE(NATIVE_CALL)
    {
        const vm_native *native;
        int16_t arguments[VM_MAX_NATIVE_ARGUMENTS];
        uint16_t i;

        operand = word & VM_OPERAND_MASK;
        if (operand >= vm->natives.count) {
            error = error_unknown_native;
            goto node_error;
        }
        native = vm->natives.natives[operand];
        if (native->stack_words > VM_MAX_NATIVE_ARGUMENTS) {
            error = error_unknown_native;
            goto node_error;
        }
        NEED_VALUES(native->stack_words);
        for (i = 0; i < native->stack_words; i++)
            arguments[i] = stack[sp--];
        vm->pc = pc;
        vm->sp = sp;
        native->function(vm, arguments);
        pc++;
        // A native may have stopped the event (an error) or, in a run,
        // cleared EVENT_RUNNING to end the run after this instruction.
        if (!(vm->flags & VM_FLAG_EVENT_ACTIVE)) {
            vm->pc = pc;
            return RUN_ERROR;
        }
        if (running && !(vm->flags & VM_FLAG_EVENT_RUNNING)) {
            vm->pc = pc;
            return RUN_INTERRUPTED;
        }
        VM_NEXT();
    }

    VM_CASE(SUB_CALL)
    {
        NEED_ROOM(1);
        stack[++sp] = (int16_t)(pc + 1);
        pc = word & VM_OPERAND_MASK;
        VM_NEXT();
    }

    VM_CASE(SUB_RET)
    {
        NEED_VALUES(1);
        pc = (uint16_t)stack[sp--];
        VM_NEXT();
    }

#if VM_USE_COMPUTED_GOTO
opcode_INVALID
  :
#else
default:
#endif
{
    error = error_unknown_bytecode;
    goto node_error;
}

    VM_LOOP_END

budget_spent:
    vm->pc = pc;
    vm->sp = sp;
    return RUN_BUDGET_SPENT;

breakpoint_hit:
    // EVENT_RUNNING stays set, as upstream reports it (flags 7).
    vm->pc = pc;
    vm->sp = sp;
    vm->flags |= VM_FLAG_STEP_BY_STEP;
    vm->callbacks->execution_state_changed(vm->context, pc, vm->flags);
    return RUN_BREAKPOINT;

array_out_of_bounds:
    // pc stays on the faulty instruction (bytecode.md §8.1).
    vm->pc = pc;
    vm->sp = sp;
    vm_error_array_access(vm, bytecode[pc + 1], (uint16_t)stack[sp]);
    return RUN_ERROR;

stack_overflow:
    error = error_stack_overflow;
    goto node_error;
stack_underflow:
    error = error_stack_underflow;
    goto node_error;
variables_out_of_bounds:
    error = error_variables_bounds;
    goto node_error;
bytecode_out_of_bounds:
    error = error_bytecode_bounds;
    goto node_error;
unknown_operator:
    error = error_unknown_operator;
node_error:
    vm->pc = pc;
    vm->sp = sp;
    vm_error_node_specific(vm, error);
    return RUN_ERROR;
}

bool vm_run(vm_state *vm, uint16_t step_budget)
{
    enum run_outcome outcome;

    if (!(vm->flags & VM_FLAG_EVENT_ACTIVE) || (vm->flags & VM_FLAG_STEP_BY_STEP))
        return false;
    vm->flags |= VM_FLAG_EVENT_RUNNING;
    do
        outcome = execute(vm, step_budget != 0 ? step_budget : UINT16_MAX, true);
    while (outcome == RUN_BUDGET_SPENT && step_budget == 0);
    if (outcome != RUN_BREAKPOINT)
        vm->flags &= (uint16_t)~VM_FLAG_EVENT_RUNNING;
    return true;
}

bool vm_step(vm_state *vm)
{
    if (!(vm->flags & VM_FLAG_EVENT_ACTIVE))
        return false;
    execute(vm, 1, false);
    return true;
}
