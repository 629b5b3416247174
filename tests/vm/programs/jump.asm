; JUMP adds its signed 12-bit operand to its own address (bytecode.md §5).
event init start
start:
    JUMP forward        ; at 3
back:
    SMALL_IMMEDIATE 2   ; at 4
    STORE 41
    STOP
forward:
    SMALL_IMMEDIATE 1   ; at 7
    STORE 40
    .word 0x9FFB        ; JUMP -5 by hand: to 4
    STOP
# expect var[40] = [1, 2]
# expect pc 6
