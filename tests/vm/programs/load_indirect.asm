; LOAD_INDIRECT base, size replaces the index on top of the stack by
; V[base + index] (bytecode.md §5).
event init start
start:
    SMALL_IMMEDIATE 0
    LOAD_INDIRECT 50 4
    STORE 40
    SMALL_IMMEDIATE 3
    LOAD_INDIRECT 50 4
    STORE 41
    LOAD 60             ; index from a variable: 2
    LOAD_INDIRECT 50 4
    STORE 42
    SMALL_IMMEDIATE 1
    LOAD_INDIRECT 50 2
    SMALL_IMMEDIATE 0
    LOAD_INDIRECT 51 1
    STORE 44
    STORE 43
    STOP
# set var[50] = [11, 22, 33, 44]
# set var[60] = 2
# expect var[40] = [11, 44, 33, 22, 22]
# expect sp -1
# expect flags 0
