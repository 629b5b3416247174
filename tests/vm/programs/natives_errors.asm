; A native that raises an error stops the VM (§8.3); the report carries the
; pc of the NATIVE_CALL, and pc moves on by one after the native returns
; (§9), as upstream does. An address a native reaches through vm_variables
; is checked when it runs. (A native index past the table is refused when
; the program arrives: verifier_test.cpp.)
event init fail
event 0 reach
fail:
    NATIVE_CALL 2       ; at 5: test.fail
    SMALL_IMMEDIATE 1
    STORE 40
    STOP
reach:
    SMALL_IMMEDIATE 5   ; length
    SMALL_IMMEDIATE 60  ; address: 60 + 5 > 64 variables
    NATIVE_CALL 3       ; at 11: test.reach, through vm_variables
    STOP
# expect error node_specific pc=5 "test failure"
# expect pc 6
# expect flags 2
# expect var[40] = 0
# run event 0
# continue
# expect error node_specific pc=11 "out of variables bounds"
# expect flags 2
# expect var[60] = [0, 0, 0, 0]
