; Code that would run off the end of the bytecode (size 7, no STOP) is
; refused by the verifier when it arrives: RUN reports "out of bytecode
; bounds" (bytecode.md §8.5) at its last instruction, and nothing runs.
# memory bytecode=7
event init off_end
off_end:
    SMALL_IMMEDIATE 1   ; at 3
    STORE 40
    SMALL_IMMEDIATE 2
    STORE 41            ; at 6, the last word
# expect error node_specific pc=6 "out of bytecode bounds"
# expect var[40] = [0, 0]
# expect flags 2
# expect pc 6
