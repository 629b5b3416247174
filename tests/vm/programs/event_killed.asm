; A new event while one is active kills it with EVENT_EXECUTION_KILLED and
; the current pc (§6.1, §8.4), and starts with an empty stack.
# budget 100
event 0 endless
event 1 second
endless:
    SMALL_IMMEDIATE 1   ; at 5
    STORE 40
loop:
    JUMP loop           ; at 7
second:
    SMALL_IMMEDIATE 2   ; 8
    SMALL_IMMEDIATE 3
    STORE 41
    STORE 42
    STOP                ; at 12
# run event 0
# expect flags 1
# expect pc 7
# run event 1
# expect killed pc=7
# expect var[40] = [1, 3, 2]
# expect flags 0
# expect pc 12
# expect sp -1
; an event that is not handled kills nothing
# run event 0
# run event 9
# expect flags 1
# expect no message
