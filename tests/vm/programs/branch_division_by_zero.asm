; A hand-made CONDITIONAL_BRANCH with DIV by zero (bytecode.md §5, §8.2):
; the result is 0, so the false path is taken and the was-true bit cleared,
; then the VM stops with DIVISION_BY_ZERO at the branch's pc.
event init start
start:
    SMALL_IMMEDIATE 5   ; at 3
    SMALL_IMMEDIATE 0
    CONDITIONAL_BRANCH MOD false was_true    ; at 5
    SMALL_IMMEDIATE 1
    STORE 40
    STOP
false:
    SMALL_IMMEDIATE 2   ; at 10
    STORE 40
    STOP
# set var[40] = 3
# expect error division_by_zero pc=5
# expect pc 10
# expect sp -1
# expect flags 2
# expect var[40] = 3
# expect bytecode[5] = 0xA006
