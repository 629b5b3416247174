; The false displacement is a full int16 word relative to the branch; the
; operator's bits 11..8 other than is-when/was-true are not produced by
; compilers, so only those two flags are used here.
event init start
back:
    SMALL_IMMEDIATE 7
    STORE 41
    STOP
start:
    SMALL_IMMEDIATE 1   ; at 6
    SMALL_IMMEDIATE 2
    CONDITIONAL_BRANCH EQUAL back   ; at 8, displacement -5
    STOP
# expect bytecode[9] = -5
# expect var[41] = 7
# expect pc 5
