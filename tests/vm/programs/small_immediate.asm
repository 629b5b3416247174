; SMALL_IMMEDIATE pushes its 12-bit operand sign-extended (bytecode.md §3, §5).
event init start
start:
    SMALL_IMMEDIATE 0
    STORE 40
    SMALL_IMMEDIATE 1
    STORE 41
    SMALL_IMMEDIATE -1
    STORE 42
    SMALL_IMMEDIATE 2047
    STORE 43
    SMALL_IMMEDIATE -2047
    STORE 44
    SMALL_IMMEDIATE -2048
    STORE 45
    .word 0x1800        ; -2048 written by hand
    STORE 46
    STOP
# expect var[40] = [0, 1, -1, 2047, -2047, -2048, -2048]
