; A push onto a full stack (4 words here) stops the VM with "stack
; overflow" (bytecode.md §8.5), for each pushing instruction.
# memory stack=4
event init small
event 0 large
event 1 load
event 2 call
event 3 recursion
small:
    SMALL_IMMEDIATE 1   ; 11
    SMALL_IMMEDIATE 2
    SMALL_IMMEDIATE 3
    SMALL_IMMEDIATE 4
    SMALL_IMMEDIATE 5   ; at 15
    STOP
large:
    SMALL_IMMEDIATE 1   ; 17
    SMALL_IMMEDIATE 2
    SMALL_IMMEDIATE 3
    SMALL_IMMEDIATE 4
    LARGE_IMMEDIATE 5   ; at 21
    STOP
load:
    SMALL_IMMEDIATE 1   ; 24
    SMALL_IMMEDIATE 2
    SMALL_IMMEDIATE 3
    SMALL_IMMEDIATE 4
    LOAD 40             ; at 28
    STOP
call:
    SMALL_IMMEDIATE 1   ; 30
    SMALL_IMMEDIATE 2
    SMALL_IMMEDIATE 3
    SMALL_IMMEDIATE 4
    SUB_CALL leaf       ; at 34: no room for the return address
    STOP
recursion:
    SUB_CALL recursion  ; at 36: the fifth call overflows
    SUB_RET
leaf:
    SUB_RET
# expect error node_specific pc=15 "stack overflow"
# expect flags 2
# expect sp 3
# run event 0
# continue
# expect error node_specific pc=21 "stack overflow"
# run event 1
# continue
# expect error node_specific pc=28 "stack overflow"
# run event 2
# continue
# expect error node_specific pc=34 "stack overflow"
# run event 3
# continue
# expect error node_specific pc=36 "stack overflow"
# expect sp 3
# expect flags 2
