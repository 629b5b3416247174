; STORE_INDIRECT base, size: index on top, value below; V[base + index] =
; value, both popped (bytecode.md §5).
event init start
start:
    SMALL_IMMEDIATE 7
    SMALL_IMMEDIATE 0
    STORE_INDIRECT 50 3
    SMALL_IMMEDIATE -8
    SMALL_IMMEDIATE 2
    STORE_INDIRECT 50 3
    LARGE_IMMEDIATE 0x7FFF
    LOAD 60             ; 1
    STORE_INDIRECT 50 3
    STOP
# set var[53] = 4
# set var[60] = 1
# expect var[50] = [7, 32767, -8, 4]
# expect sp -1
