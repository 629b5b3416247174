; An index (as uint16) >= size stops the VM with ARRAY_ACCESS_OUT_OF_BOUNDS
; (pc, size, index); pc stays on the instruction (bytecode.md §8.1).
event init at_size
event 0 negative
event 1 zero_size
at_size:
    SMALL_IMMEDIATE 4   ; at 7
    LOAD_INDIRECT 50 4  ; at 8
    STORE 40
    STOP
negative:
    SMALL_IMMEDIATE -1  ; at 12
    LOAD_INDIRECT 50 4  ; at 13
    STORE 40
    STOP
zero_size:
    SMALL_IMMEDIATE 0   ; at 17
    LOAD_INDIRECT 50 0  ; at 18
    STORE 40
    STOP
# set var[40] = 9
# expect error array_access pc=8 size=4 index=4
# expect pc 8
# expect flags 2
# expect var[40] = 9
# run event 0
# continue
# expect error array_access pc=13 size=4 index=65535
# expect pc 13
# expect flags 2
# run event 1
# continue
# expect error array_access pc=18 size=0 index=0
# expect pc 18
# expect var[40] = 9
