; The spec's verified example (bytecode.md §8.1): `arr[i] = 1` with arr of
; size 3 and i = 3, the STORE_INDIRECT at pc 9, gives payload (9, 3, 3); pc
; is not advanced and nothing is written.
event init start
event 0 negative
.word 0 0                ; padding so that the store is at 9
start:
    SMALL_IMMEDIATE 1   ; at 7
    LOAD 40             ; i, at 8
    STORE_INDIRECT 36 3 ; at 9
    STOP
negative:
    SMALL_IMMEDIATE 1   ; at 12
    LARGE_IMMEDIATE -32768
    STORE_INDIRECT 36 3 ; at 15
    STOP
# set var[40] = 3
# set var[36] = [5, 5, 5, 5]
# expect error array_access pc=9 size=3 index=3
# expect pc 9
# expect flags 2
# expect var[36] = [5, 5, 5, 5]
# run event 0
# continue
# expect error array_access pc=15 size=3 index=32768
# expect pc 15
# expect var[36] = [5, 5, 5, 5]
