; LOAD and STORE of an address outside the variables stop the VM with
; NODE_SPECIFIC_ERROR "out of variables bounds" (bytecode.md §8.5).
event init load_outside
event 0 store_outside
event 1 store_far
load_outside:
    LOAD 64             ; variables are 0..63; at address 7
    STORE 40
    STOP
store_outside:
    SMALL_IMMEDIATE 5   ; at 10
    STORE 64
    STOP
store_far:
    SMALL_IMMEDIATE 5   ; at 13
    STORE 4095
    STOP
# set var[40] = 3
# expect error node_specific pc=7 "out of variables bounds"
# expect flags 2
# expect pc 7
# expect var[40] = 3
# run event 0
# continue
# expect error node_specific pc=11 "out of variables bounds"
# expect flags 2
# run event 1
# continue
# expect error node_specific pc=14 "out of variables bounds"
# expect flags 2
