; SUB_CALL pushes pc + 1 and jumps to its absolute operand; SUB_RET pops the
; return address (bytecode.md §5). Nested calls; the stack is empty after.
event init start
start:
    SMALL_IMMEDIATE 5   ; at 3
    SUB_CALL double     ; at 4, returns to 5
    SUB_CALL double
    STORE 40            ; (5 * 2) * 2 = 20
    SUB_CALL outer      ; at 7
    STOP                ; at 8
double:                 ; stack: value, return address
    STORE 50            ; return address
    SMALL_IMMEDIATE 2
    BINARY_ARITHMETIC MULT
    LOAD 50
    SUB_RET
outer:
    LOAD 63             ; the return address is below: sp 0 holds 8
    SUB_CALL inner
    STORE 41
    SUB_RET
inner:
    STORE 51            ; return address of inner
    SMALL_IMMEDIATE 1
    BINARY_ARITHMETIC ADD
    LOAD 51
    SUB_RET
# set var[63] = 99
# expect var[40] = 20
# expect var[41] = 100
# expect var[50] = 6
# expect pc 8
# expect sp -1
