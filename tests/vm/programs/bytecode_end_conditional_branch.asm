; CONDITIONAL_BRANCH cut by the end of the bytecode (size 6): its operand
; words would be read past the array, so the VM stops with "out of
; bytecode bounds" (bytecode.md §8.5) before doing anything.
# memory bytecode=6
event init start
start:
    SMALL_IMMEDIATE 5
    SMALL_IMMEDIATE 5
    .word 0xA00A
# set var[40] = 5
# expect error node_specific pc=* "out of bytecode bounds"
# expect flags 2
# expect var[40] = 5
