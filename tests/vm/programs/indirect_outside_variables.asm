; An index inside the declared size that still falls outside the variables
; stops the VM with "out of variables bounds" (bytecode.md §8.5).
event init load
event 0 store
load:
    SMALL_IMMEDIATE 5   ; at 5
    LOAD_INDIRECT 60 10 ; 60 + 5 >= 64, at 6
    STORE 40
    STOP
store:
    SMALL_IMMEDIATE 1   ; at 10
    SMALL_IMMEDIATE 4   ; at 11
    STORE_INDIRECT 60 8 ; at 12
    STOP
# expect error node_specific pc=6 "out of variables bounds"
# expect flags 2
# run event 0
# continue
# expect error node_specific pc=12 "out of variables bounds"
# expect flags 2
