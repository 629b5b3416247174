; Code that runs off the end of the bytecode (size 7, no STOP) stops the VM
; with "out of bytecode bounds" (bytecode.md §8.5) after its last word ran.
# memory bytecode=7
event init off_end
off_end:
    SMALL_IMMEDIATE 1   ; at 3
    STORE 40
    SMALL_IMMEDIATE 2
    STORE 41            ; at 6, the last word
# expect error node_specific pc=* "out of bytecode bounds"
# expect var[40] = [1, 2]
# expect flags 2
