; Popping an empty stack stops the VM with "stack underflow" (§8.5), for
; each instruction that pops.
event init store
event 0 binary
event 1 unary
event 2 load_indirect
event 3 store_indirect
event 4 branch
event 5 sub_ret
event 6 native
store:
    STORE 40            ; at 17
binary:
    SMALL_IMMEDIATE 1   ; 18
    BINARY_ARITHMETIC ADD   ; at 19
unary:
    UNARY_ARITHMETIC SUB    ; at 20
load_indirect:
    LOAD_INDIRECT 40 2  ; at 21
store_indirect:
    SMALL_IMMEDIATE 0   ; 23
    STORE_INDIRECT 40 2 ; at 24
branch:
    SMALL_IMMEDIATE 0   ; 26
    CONDITIONAL_BRANCH EQUAL 2  ; at 27
sub_ret:
    SUB_RET             ; at 29
native:
    SMALL_IMMEDIATE 40  ; 30
    SMALL_IMMEDIATE 41
    NATIVE_CALL 0       ; at 32: subtract takes 3 words
# set var[40] = 7
# expect error node_specific pc=17 "stack underflow"
# expect flags 2
# run event 0
# continue
# expect error node_specific pc=19 "stack underflow"
# run event 1
# continue
# expect error node_specific pc=20 "stack underflow"
# run event 2
# continue
# expect error node_specific pc=21 "stack underflow"
# run event 3
# continue
# expect error node_specific pc=24 "stack underflow"
# run event 4
# continue
# expect error node_specific pc=27 "stack underflow"
# run event 5
# continue
# expect error node_specific pc=29 "stack underflow"
# run event 6
# continue
# expect error node_specific pc=32 "stack underflow"
# expect flags 2
# expect var[40] = [7, 0]
