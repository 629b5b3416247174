; EMIT cut by the end of the bytecode (size 5): its operand words
; would lie past the array. The verifier refuses the program when it
; arrives; RUN reports "out of bytecode bounds" at the cut instruction
; (bytecode.md §8.5) and nothing runs.
# memory bytecode=5
event init start
start:
    .word 0xB001 40
# set var[40] = 5
# expect error node_specific pc=3 "out of bytecode bounds"
# expect flags 2
# expect var[40] = 5
