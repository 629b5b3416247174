; LARGE_IMMEDIATE pushes its second word as int16; the operand bits of the
; first word are ignored (bytecode.md §3).
event init start
start:
    LARGE_IMMEDIATE -32768
    STORE 40
    LARGE_IMMEDIATE 32767
    STORE 41
    LARGE_IMMEDIATE 0xFFFF
    STORE 42
    LARGE_IMMEDIATE -3000
    STORE 43
    .word 0x2ABC 0x1234
    STORE 44
    LARGE_IMMEDIATE 0
    STORE 45
    STOP
# set var[45] = 5
# expect var[40] = [-32768, 32767, -1, -3000, 0x1234, 0]
