; A JUMP out of the bytecode, forward or backward (wrapping below 0), stops
; the VM with "out of bytecode bounds" (bytecode.md §8.5). The spec does not
; say which pc the report carries, hence `*`.
# memory bytecode=64
event init forward
event 0 backward
event 1 zero
forward:
    JUMP 2047           ; at 7
backward:
    JUMP -2048          ; at 8
zero:
    JUMP -9             ; at 9: to 0, whose word 0x0007 decodes as STOP
# expect error node_specific pc=* "out of bytecode bounds"
# expect flags 2
# run event 0
# continue
# expect error node_specific pc=* "out of bytecode bounds"
# expect flags 2
# run event 1
# continue
# expect pc 0
# expect flags 0
