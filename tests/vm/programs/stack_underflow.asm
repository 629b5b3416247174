; A SUB_RET with no return address, reached in an event that made no call,
; stops the VM with "stack underflow" (§8.5). (Every other pop of a value
; that is not there is refused when the program arrives: verifier_test.cpp.)
event init start
start:
    SMALL_IMMEDIATE 7
    STORE 40
    SUB_RET             ; at 5
# expect error node_specific pc=5 "stack underflow"
# expect flags 2
# expect sp -1
# expect var[40] = 7
