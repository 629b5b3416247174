; Division and modulo by zero (bytecode.md §8.2): 0 is pushed, pc moves past
; the instruction, the VM stops and DIVISION_BY_ZERO names the faulty pc.
event init divide
event 0 modulo
divide:
    SMALL_IMMEDIATE 5   ; at 5
    SMALL_IMMEDIATE 0
    BINARY_ARITHMETIC DIV   ; at 7
    STORE 40
    STOP
modulo:
    SMALL_IMMEDIATE 9   ; at 10
    LOAD 41
    BINARY_ARITHMETIC MOD   ; at 12
    STORE 40
    STOP
# set var[40] = 3
# expect error division_by_zero pc=7
# expect pc 8
# expect sp 0
# expect flags 2
# expect var[40] = 3
; the VM stays stopped: a later run does nothing
# run
# expect pc 8
# expect no message
; RUN does not resume it: the error ended the event
# continue
# expect pc 8
# expect var[40] = 3
# run event 0
# expect error division_by_zero pc=12
# expect pc 13
# expect flags 2
