; Clearing EVENT_RUNNING while the run loop runs (as an interrupt may; here
; native 4 does it) makes the loop exit after the current instruction
; (bytecode.md §6, §6.2 step 3): the handler stays active, pc after the call,
; and the next run goes on from there.
event init start
start:
    SMALL_IMMEDIATE 1
    STORE 40
    NATIVE_CALL 4       ; at 5
    SMALL_IMMEDIATE 2   ; at 6
    STORE 41
    STOP                ; at 8
# expect var[40] = [1, 0]
# expect pc 6
# expect flags 1
# run
# expect var[40] = [1, 2]
# expect pc 8
# expect flags 0
