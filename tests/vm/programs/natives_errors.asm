; A native that raises an error stops the VM (§8.3); the report carries the
; pc of the NATIVE_CALL, and pc moves on by one after the native returns
; (§9), as upstream does. A native index past the table is an error too
; (§8.5: bad addresses).
event init fail
event 0 unknown
event 1 unknown_far
event 2 reach
fail:
    NATIVE_CALL 2       ; at 9: test.fail
    SMALL_IMMEDIATE 1
    STORE 40
    STOP
unknown:
    NATIVE_CALL 12      ; at 13: the harness has natives 0..11
    STOP
unknown_far:
    NATIVE_CALL 4095    ; at 15
    STOP
reach:
    SMALL_IMMEDIATE 5   ; length
    SMALL_IMMEDIATE 60  ; address: 60 + 5 > 64 variables
    NATIVE_CALL 3       ; at 19: test.reach, through vm_variables
    STOP
# expect error node_specific pc=9 "test failure"
# expect pc 10
# expect flags 2
# expect var[40] = 0
# run event 0
# continue
# expect error node_specific pc=13
# expect flags 2
# run event 1
# continue
# expect error node_specific pc=15
# run event 2
# continue
# expect error node_specific pc=19 "out of variables bounds"
# expect flags 2
# expect var[60] = [0, 0, 0, 0]
