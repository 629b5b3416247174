// The Aseba interpreter: event setup and the run loop (bytecode.md §2-§9).
//
// The loop runs only bytecode that the verifier accepted (vm_verify.c), so
// it checks nothing the verifier proved: pc always lies on an instruction of
// the code, every direct address inside the variables, every pop finds its
// value. It checks what depends on run-time values: the step budget, stack
// room on each push, an indirect index against its array's size, division by
// zero, SUB_RET outside a call. The hot state (pc and the stack top as
// pointers) lives in locals, written back only where the outside world can
// look: at natives, emits, errors, the end of the event and when the budget
// runs out. Breakpoints cost the loop nothing: with any set, vm_run steps
// one instruction at a time and checks them in between.

#include "vm_internal.h"
#include "vm_opcodes.h"

#include <stddef.h>

const char vm_error_stack_overflow[] = "stack overflow";
const char vm_error_stack_underflow[] = "stack underflow";
const char vm_error_variables_bounds[] = "out of variables bounds";
const char vm_error_bytecode_bounds[] = "out of bytecode bounds";
const char vm_error_unknown_bytecode[] = "unknown bytecode";
const char vm_error_unknown_operator[] = "unknown operator";
const char vm_error_unknown_native[] = "unknown native function";
const char vm_error_event_too_large[] = "emitted event too large";
const char vm_error_invalid_jump[] = "invalid jump";

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
    vm->rejection = NULL;
    vm->rejection_pc = 0;
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
        vm_report(vm, VM_REPORT_EVENT_EXECUTION_KILLED, 1, 0);
    vm->pc = address;
    vm->sp = -1;
    vm->flags |= VM_FLAG_EVENT_ACTIVE;
    if (vm->flags & VM_FLAG_STEP_BY_STEP)
        vm_report_state(vm);
    return address;
}

void vm_report(vm_state *vm, uint16_t type, uint16_t count, uint16_t second)
{
    uint16_t words[2];

    words[0] = vm->pc;
    words[1] = second;
    vm->callbacks->report(vm->context, type, words, count);
}

// --- errors: each stops the VM and sends one report --------------------------

void vm_error_array_access(vm_state *vm, uint16_t size, uint16_t index)
{
    uint16_t words[3];

    vm->flags = VM_FLAG_STEP_BY_STEP;
    words[0] = vm->pc;
    words[1] = size;
    words[2] = index;
    vm->callbacks->report(vm->context, VM_REPORT_ARRAY_ACCESS_OUT_OF_BOUNDS, words, 3);
}

void vm_error_division_by_zero(vm_state *vm)
{
    vm->flags = VM_FLAG_STEP_BY_STEP;
    vm_report(vm, VM_REPORT_DIVISION_BY_ZERO, 1, 0);
}

void vm_error_node_specific(vm_state *vm, const char *message)
{
    vm->flags = VM_FLAG_STEP_BY_STEP;
    vm->callbacks->node_specific_error(vm->context, vm->pc, message);
}

void vm_report_rejection(vm_state *vm)
{
    vm->pc = vm->rejection_pc;
    vm_error_node_specific(vm, vm->rejection);
}

int16_t *vm_variables(vm_state *vm, uint16_t address, uint16_t length)
{
    // An empty span touches nothing: any address will do, as upstream.
    if (length == 0)
        return vm->memory.variables;
    if (address >= vm->memory.variables_size || length > vm->memory.variables_size - address) {
        vm_error_node_specific(vm, vm_error_variables_bounds);
        return NULL;
    }
    return vm->memory.variables + address;
}

// --- arithmetic (bytecode.md §4) ---------------------------------------------

// Upstream computes on operands promoted to 32 bits and truncates the result
// to 16. The same results come from 16-bit operations on unsigned words
// (whose wrap-around is defined C) with the few cases where 32 bits differ
// made explicit: shifts by 16 or more, and -32768 / -1. That is one machine
// operation instead of a 32-bit library call on a 16-bit chip.

static inline int16_t word_sum(int16_t a, int16_t b)
{
    return (int16_t)(uint16_t)((unsigned)(uint16_t)a + (uint16_t)b);
}

static inline int16_t word_difference(int16_t a, int16_t b)
{
    return (int16_t)(uint16_t)((unsigned)(uint16_t)a - (uint16_t)b);
}

static inline int16_t word_product(int16_t a, int16_t b)
{
    return (int16_t)(uint16_t)((unsigned)(uint16_t)a * (uint16_t)b);
}

static inline int16_t word_negation(int16_t a)
{
    return (int16_t)(uint16_t)(0u - (uint16_t)a);
}

// The count is taken modulo 32, as the 32-bit shift upstream compiles to.
static inline int16_t shift_left(int16_t a, int16_t b)
{
    uint16_t count = (uint16_t)b & 31u;

    return count >= 16 ? 0 : (int16_t)(uint16_t)((unsigned)(uint16_t)a << count);
}

// Arithmetic shift (gcc and XC16 shift signed values arithmetically).
static inline int16_t shift_right(int16_t a, int16_t b)
{
    uint16_t count = (uint16_t)b & 31u;

    return (int16_t)(a >> (count >= 15 ? 15 : count));
}

// Divisor not 0. -32768 / -1 is 32768, truncated back to -32768.
static inline int16_t quotient(int16_t a, int16_t b)
{
    return b == -1 ? word_negation(a) : (int16_t)(a / b);
}

static inline int16_t remainder_of(int16_t a, int16_t b)
{
    return b == -1 ? 0 : (int16_t)(a % b);
}

// DIV or MOD, as the instruction `word` says, by a divisor that is not 0.
static inline int16_t divide(unsigned word, int16_t a, int16_t b)
{
    return (word & VM_OPERATOR_MASK) == VM_BINARY_DIV ? quotient(a, b) : remainder_of(a, b);
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

// The binary operators whose result is an expression of a and b; DIV and MOD,
// which may fail, are written out in the loop.
#define VM_SIMPLE_BINARY_OPERATORS(X)                                                              \
    X(SHIFT_LEFT, shift_left(a, b))                                                                \
    X(SHIFT_RIGHT, shift_right(a, b))                                                              \
    X(ADD, word_sum(a, b))                                                                         \
    X(SUB, word_difference(a, b))                                                                  \
    X(MULT, word_product(a, b))                                                                    \
    X(BIT_OR, (int16_t)(a | b))                                                                    \
    X(BIT_XOR, (int16_t)(a ^ b))                                                                   \
    X(BIT_AND, (int16_t)(a & b))                                                                   \
    X(EQUAL, a == b)                                                                               \
    X(NOT_EQUAL, a != b)                                                                           \
    X(BIGGER_THAN, a > b)                                                                          \
    X(BIGGER_EQUAL_THAN, a >= b)                                                                   \
    X(SMALLER_THAN, a < b)                                                                         \
    X(SMALLER_EQUAL_THAN, a <= b)                                                                  \
    X(OR, a != 0 || b != 0)                                                                        \
    X(AND, a != 0 && b != 0)

// The dispatch is written once and compiles as a switch (the reference, for
// compilers without `&&label`) or, with VM_USE_COMPUTED_GOTO, as jumps
// through tables of labels (and then operators too, on bits 7..0).
// Computed goto counts the budget (at least 1) after each instruction, in
// each one's code: one decrement and a branch, and the count fits the word
// it was given in.
#if VM_USE_COMPUTED_GOTO
#define VM_LOOP_BEGIN VM_DISPATCH();
#define VM_LOOP_END
#define VM_DISPATCH()                                                                              \
    do {                                                                                           \
        word = *ip;                                                                                \
        goto *opcode_table[word >> VM_OPCODE_SHIFT];                                               \
    } while (0)
#define VM_CASE(name) opcode_##name:
#define VM_NEXT()                                                                                  \
    if (--remaining != 0)                                                                          \
        VM_DISPATCH();                                                                             \
    else                                                                                           \
        goto budget_spent
#else
// The switch counts the budget once, before each instruction: less code.
#define VM_LOOP_BEGIN                                                                              \
    for (;;) {                                                                                     \
        if (remaining-- == 0)                                                                      \
            goto budget_spent;                                                                     \
        word = *ip;                                                                                \
        switch (word >> VM_OPCODE_SHIFT) {
#define VM_LOOP_END                                                                                \
    }                                                                                              \
    }
#define VM_CASE(name) case VM_OP_##name:
#define VM_NEXT()     continue
#endif

#define PUSH(value)                                                                                \
    do {                                                                                           \
        if (next == stack_end)                                                                     \
            goto stack_overflow;                                                                   \
        *next++ = (value);                                                                         \
    } while (0)

// pc and sp for the outside world, from the run loop's pointers.
static void save_state(vm_state *vm, const uint16_t *ip, const int16_t *next)
{
    vm->pc = (uint16_t)(ip - vm->memory.bytecode);
    vm->sp = (int16_t)(next - vm->memory.stack - 1);
}

// Runs at most `budget` instructions of the active event, whose bytecode the
// verifier accepted. A run (as opposed to a single step) ends when a native
// clears EVENT_RUNNING.
static enum run_outcome execute(vm_state *vm, uint16_t budget, bool running)
{
    uint16_t *const bytecode = vm->memory.bytecode;
    int16_t *const variables = vm->memory.variables;
    // The stack's base is left out of the locals: only cold paths need it.
    int16_t *const stack_end = vm->memory.stack + vm->memory.stack_size;
    unsigned remaining = budget; // at least 1; `unsigned`: the chip's natural width
    uint16_t *ip = bytecode + vm->pc;
    int16_t *next = vm->memory.stack + (vm->sp + 1); // the first free stack word
    unsigned word;
    int16_t a = 0, b = 0; // operands (initialised for the compiler's flow analysis)
    const char *error;
    enum run_outcome outcome;

#if VM_USE_COMPUTED_GOTO
    static const void *const opcode_table[16] = {
#define VM_OPCODE_LABEL(name, code, words, stack, meaning) [code] = &&opcode_##name,
        VM_OPCODE_LIST(VM_OPCODE_LABEL)
#undef VM_OPCODE_LABEL
          [VM_OP_INVALID] = &&unknown_bytecode,
    };
    // The verifier admits operators below VM_BINARY_OPERATOR_COUNT only; the
    // tables still cover every value of their index, so that a fault of the
    // verifier could never send the loop elsewhere than to a label of its own.
#define VM_OPERATOR_LABEL(name, expression) [VM_BINARY_##name] = &&arithmetic_##name,
    static const void *const arithmetic_table[VM_OPERATOR_MASK + 1] = {
        [VM_BINARY_OPERATOR_COUNT... VM_OPERATOR_MASK] = &&unknown_operator,
        [VM_BINARY_DIV] = &&arithmetic_DIV,
        [VM_BINARY_MOD] = &&arithmetic_MOD,
        VM_SIMPLE_BINARY_OPERATORS(VM_OPERATOR_LABEL)
    };
#undef VM_OPERATOR_LABEL
#define VM_OPERATOR_LABEL(name, expression) [VM_BINARY_##name] = &&branch_##name,
    static const void *const branch_table[VM_OPERATOR_MASK + 1] = {
        [VM_BINARY_OPERATOR_COUNT... VM_OPERATOR_MASK] = &&unknown_operator,
        [VM_BINARY_DIV] = &&branch_DIV,
        [VM_BINARY_MOD] = &&branch_MOD,
        VM_SIMPLE_BINARY_OPERATORS(VM_OPERATOR_LABEL)
    };
#undef VM_OPERATOR_LABEL
#endif

    VM_LOOP_BEGIN

    VM_CASE(STOP)
    {
        vm->flags &= (uint16_t)~VM_FLAG_EVENT_ACTIVE;
        outcome = RUN_EVENT_ENDED;
        goto leave;
    }

    VM_CASE(SMALL_IMMEDIATE)
    {
        // Sign-extend the 12-bit operand.
        PUSH((int16_t)(uint16_t)(word << 4) >> 4);
        ip++;
        VM_NEXT();
    }

    VM_CASE(LARGE_IMMEDIATE)
    {
        PUSH((int16_t)ip[1]);
        ip += 2;
        VM_NEXT();
    }

    VM_CASE(LOAD)
    {
        PUSH(variables[word & VM_OPERAND_MASK]);
        ip++;
        VM_NEXT();
    }

    VM_CASE(STORE)
    {
        variables[word & VM_OPERAND_MASK] = *--next;
        ip++;
        VM_NEXT();
    }

    VM_CASE(LOAD_INDIRECT)
    {
        // The verifier put the whole array inside the variables.
        uint16_t index = (uint16_t)next[-1];

        if (index >= ip[1])
            goto array_out_of_bounds;
        next[-1] = (variables + (word & VM_OPERAND_MASK))[index];
        ip += 2;
        VM_NEXT();
    }

    VM_CASE(STORE_INDIRECT)
    {
        uint16_t index = (uint16_t)next[-1];

        if (index >= ip[1])
            goto array_out_of_bounds;
        (variables + (word & VM_OPERAND_MASK))[index] = next[-2];
        next -= 2;
        ip += 2;
        VM_NEXT();
    }

    VM_CASE(UNARY_ARITHMETIC)
    {
        a = next[-1];
        switch (word & VM_OPERATOR_MASK) {
        case VM_UNARY_SUB: a = word_negation(a); break;
        case VM_UNARY_ABS: a = a < 0 ? word_negation(a) : a; break;
        case VM_UNARY_BIT_NOT: a = (int16_t)~a; break;
        default: goto unknown_operator;
        }
        next[-1] = a;
        ip++;
        VM_NEXT();
    }

#if VM_USE_COMPUTED_GOTO
    // Each operator has its own code in each of the two instructions that
    // use operators: the fastest dispatch.
    VM_CASE(BINARY_ARITHMETIC)
    {
        b = next[-1];
        a = next[-2];
        goto *arithmetic_table[word & VM_OPERATOR_MASK];
#define VM_ARITHMETIC_CASE(name, expression)                                                       \
    arithmetic_##name:                                                                             \
    {                                                                                              \
        next[-2] = (int16_t)(expression);                                                          \
        next--;                                                                                    \
        ip++;                                                                                      \
        VM_NEXT();                                                                                 \
    }
        VM_SIMPLE_BINARY_OPERATORS(VM_ARITHMETIC_CASE)
#undef VM_ARITHMETIC_CASE
    arithmetic_DIV:
    arithmetic_MOD:
        if (b == 0)
            goto division_by_zero;
        next[-2] = divide(word, a, b);
        next--;
        ip++;
        VM_NEXT();
    }

    VM_CASE(CONDITIONAL_BRANCH)
    {
        b = next[-1];
        a = next[-2];
        goto *branch_table[word & VM_OPERATOR_MASK];
#define VM_BRANCH_CASE(name, expression)                                                           \
    branch_##name:                                                                                 \
    {                                                                                              \
        if (expression)                                                                            \
            goto branch_true;                                                                      \
        goto branch_false;                                                                         \
    }
        VM_SIMPLE_BINARY_OPERATORS(VM_BRANCH_CASE)
#undef VM_BRANCH_CASE
    branch_DIV:
    branch_MOD:
        if (b == 0)
            goto division_by_zero;
        if (divide(word, a, b) != 0)
            goto branch_true;
        goto branch_false;
    }
#else
    // The two instructions that use operators share one evaluation: the
    // smallest code.
    VM_CASE(BINARY_ARITHMETIC)
    VM_CASE(CONDITIONAL_BRANCH)
    {
        int16_t result;

        b = next[-1];
        a = next[-2];
        switch (word & VM_OPERATOR_MASK) {
#define VM_RESULT_CASE(name, expression)                                                           \
    case VM_BINARY_##name:                                                                         \
        result = (int16_t)(expression);                                                            \
        break;
            VM_SIMPLE_BINARY_OPERATORS(VM_RESULT_CASE)
#undef VM_RESULT_CASE
        case VM_BINARY_DIV:
        case VM_BINARY_MOD:
            if (b == 0)
                goto division_by_zero;
            result = divide(word, a, b);
            break;
        default: goto unknown_operator;
        }
        if ((word >> VM_OPCODE_SHIFT) == VM_OP_BINARY_ARITHMETIC) {
            next[-2] = result;
            next--;
            ip++;
            VM_NEXT();
        }
        if (result != 0)
            goto branch_true;
        goto branch_false;
    }
#endif

branch_true:
    // The operands leave the stack. The instruction word remembers the last
    // result: a `when` takes its true path only on a false-to-true edge.
    next -= 2;
    *ip = (uint16_t)(word | VM_BRANCH_WAS_TRUE_BIT);
    if ((word & (VM_BRANCH_IS_WHEN_BIT | VM_BRANCH_WAS_TRUE_BIT)) !=
        (VM_BRANCH_IS_WHEN_BIT | VM_BRANCH_WAS_TRUE_BIT)) {
        ip += 2;
        VM_NEXT();
    }
    ip += (int16_t)ip[1];
    VM_NEXT();
branch_false:
    next -= 2;
    *ip = (uint16_t)(word & ~VM_BRANCH_WAS_TRUE_BIT);
    ip += (int16_t)ip[1];
    VM_NEXT();

    VM_CASE(JUMP)
    {
        // Sign-extend the 12-bit displacement.
        ip += (int16_t)(uint16_t)(word << 4) >> 4;
        VM_NEXT();
    }

    VM_CASE(EMIT)
    {
        save_state(vm, ip, next);
        vm->callbacks->emit(vm->context, word & VM_OPERAND_MASK, variables + ip[1], ip[2]);
        ip += 3;
        VM_NEXT();
    }

    VM_CASE(NATIVE_CALL)
    {
        // The verifier let through only ids below the table's count.
        const vm_native *native = vm_native_at(&vm->natives, word & VM_OPERAND_MASK);
        int16_t arguments[VM_MAX_NATIVE_ARGUMENTS];
        uint16_t count = vm_native_stack_words(native);
        uint16_t i;

        for (i = 0; i < count; i++)
            arguments[i] = *--next;
        save_state(vm, ip, next);
        native->function(vm, arguments);
        ip++;
        // A native may have stopped the event (an error) or, in a run,
        // cleared EVENT_RUNNING to end the run after this instruction.
        if (!(vm->flags & VM_FLAG_EVENT_ACTIVE)) {
            outcome = RUN_ERROR;
            goto leave;
        }
        if (running && !(vm->flags & VM_FLAG_EVENT_RUNNING)) {
            outcome = RUN_INTERRUPTED;
            goto leave;
        }
        VM_NEXT();
    }

    VM_CASE(SUB_CALL)
    {
        PUSH((int16_t)(ip - bytecode + 1));
        ip = bytecode + (word & VM_OPERAND_MASK);
        VM_NEXT();
    }

    VM_CASE(SUB_RET)
    {
        // The verifier left only the return address on the subroutine's
        // stack; an event that never called has none.
        if (next == vm->memory.stack)
            goto stack_underflow;
        ip = bytecode + (uint16_t) * --next;
        VM_NEXT();
    }

#if !VM_USE_COMPUTED_GOTO
// Every opcode has a case, so the switch needs no range check.
case VM_OP_INVALID: goto unknown_bytecode;
#endif

    VM_LOOP_END

budget_spent:
    outcome = RUN_BUDGET_SPENT;
leave:
    save_state(vm, ip, next);
    return outcome;

division_by_zero:
    // The instruction completes with a result of 0, then the VM stops: an
    // arithmetic one leaves 0 and moves pc on, a branch takes its false path.
    // Both operands are still on the stack here. The report names the faulty
    // instruction, so pc moves on after it (one report call for both: less
    // code).
    {
        int16_t move;

        save_state(vm, ip, next);
        if ((word >> VM_OPCODE_SHIFT) == VM_OP_BINARY_ARITHMETIC) {
            next[-2] = 0;
            vm->sp--;
            move = 1;
        } else {
            vm->sp = (int16_t)(vm->sp - 2);
            *ip = (uint16_t)(word & ~VM_BRANCH_WAS_TRUE_BIT);
            move = (int16_t)ip[1];
        }
        vm_error_division_by_zero(vm);
        vm->pc = (uint16_t)(vm->pc + move);
        return RUN_ERROR;
    }

array_out_of_bounds:
    // pc stays on the faulty instruction (bytecode.md §8.1).
    save_state(vm, ip, next);
    vm_error_array_access(vm, ip[1], (uint16_t)next[-1]);
    return RUN_ERROR;

stack_overflow:
    error = vm_error_stack_overflow;
    goto node_error;
stack_underflow:
    error = vm_error_stack_underflow;
    goto node_error;
unknown_bytecode:
    error = vm_error_unknown_bytecode;
    goto node_error;
unknown_operator:
    error = vm_error_unknown_operator;
node_error:
    save_state(vm, ip, next);
    vm_error_node_specific(vm, error);
    return RUN_ERROR;
}

// A run with breakpoints set: one instruction at a time, each checked first.
static enum run_outcome run_to_breakpoint(vm_state *vm, uint16_t budget)
{
    uint16_t done = 0;
    enum run_outcome outcome;

    for (;;) {
        if (budget != 0 && done == budget)
            return RUN_BUDGET_SPENT;
        if (at_breakpoint(vm, vm->pc)) {
            // EVENT_RUNNING stays set, as upstream reports it (flags 7).
            vm->flags |= VM_FLAG_STEP_BY_STEP;
            vm_report_state(vm);
            return RUN_BREAKPOINT;
        }
        outcome = execute(vm, 1, true);
        if (outcome != RUN_BUDGET_SPENT)
            return outcome;
        done++;
    }
}

bool vm_run(vm_state *vm, uint16_t step_budget)
{
    enum run_outcome outcome;

    // A refused program never leaves STEP_BY_STEP (vm_command_run); the
    // rejection is checked again here, once per call, for callers that set
    // the flags themselves.
    if (!(vm->flags & VM_FLAG_EVENT_ACTIVE) || (vm->flags & VM_FLAG_STEP_BY_STEP) ||
        vm->rejection != NULL)
        return false;
    vm->flags |= VM_FLAG_EVENT_RUNNING;
    if (vm->breakpoint_count != 0)
        outcome = run_to_breakpoint(vm, step_budget);
    else
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
    if (vm->rejection != NULL) {
        vm_report_rejection(vm);
        return true;
    }
    execute(vm, 1, false);
    return true;
}
