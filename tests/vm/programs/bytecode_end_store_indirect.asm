; STORE_INDIRECT cut by the end of the bytecode (size 6): its operand words
; would lie past the array. The verifier refuses the program when it
; arrives; RUN reports "out of bytecode bounds" at the cut instruction
; (bytecode.md §8.5) and nothing runs.
# memory bytecode=6
event init start
start:
    SMALL_IMMEDIATE 5
    SMALL_IMMEDIATE 0
    .word 0x6028
# set var[40] = 5
# expect error node_specific pc=5 "out of bytecode bounds"
# expect flags 2
# expect var[40] = 5
