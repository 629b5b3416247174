; LARGE_IMMEDIATE cut by the end of the bytecode (size 4): its operand
; words would be read past the array, so the VM stops with "out of
; bytecode bounds" (bytecode.md §8.5) before doing anything.
# memory bytecode=4
event init start
start:
    .word 0x2000
# set var[40] = 5
# expect error node_specific pc=* "out of bytecode bounds"
# expect flags 2
# expect var[40] = 5
