; SUB_CALL pushes pc + 1 and jumps to its absolute operand; SUB_RET pops the
; return address (bytecode.md §5). A subroutine works on its own part of the
; stack, above the return address, and shares values through variables, as
; compiled code does. Nested calls, and a call with values of the caller
; still on the stack; the stack is empty after.
event init start
start:
    SMALL_IMMEDIATE 5   ; at 3
    STORE 50
    SUB_CALL double     ; at 5, returns to 6
    SUB_CALL double
    LOAD 50
    STORE 40            ; (5 * 2) * 2 = 20
    SMALL_IMMEDIATE 1
    SUB_CALL outer      ; at 10, with the 1 below its return address
    STORE 42            ; the 1, back on top
    STOP                ; at 12
double:
    LOAD 50
    SMALL_IMMEDIATE 2
    BINARY_ARITHMETIC MULT
    STORE 50
    SUB_RET
outer:
    LOAD 63
    STORE 51
    SUB_CALL inner
    LOAD 51
    STORE 41
    SUB_RET
inner:
    LOAD 51
    SMALL_IMMEDIATE 1
    BINARY_ARITHMETIC ADD
    STORE 51
    SUB_RET
# set var[63] = 99
# expect var[40] = [20, 100, 1]
# expect var[50] = 20
# expect pc 12
# expect sp -1
