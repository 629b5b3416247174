; STOP ends the event and leaves pc on itself (bytecode.md §5); its operand
; bits are ignored. The init event is not active any more: flags 0.
event init start
start:
    SMALL_IMMEDIATE 1
    STORE 40
    .word 0x0ABC        ; STOP with operand bits, at address 5
    SMALL_IMMEDIATE 2
    STORE 40
    STOP
# expect var[40] = 1
# expect pc 5
# expect flags 0
# expect sp -1
