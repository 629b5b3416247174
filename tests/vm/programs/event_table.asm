; Event lookup (§2): pairs after B[0]; an unhandled event changes nothing;
; address 0 means "not handled"; pairs past the table size are not seen.
.raw
.word 7                 ; table of 3 events
.word 0xFFFF init
.word 0 zero
.word 0x7FFF big
.word 3 three           ; beyond B[0]: not part of the table
.word 4 0               ; (never read)
init:
    SMALL_IMMEDIATE 1
    STORE 40
    STOP
zero:
    SMALL_IMMEDIATE 2
    STORE 41
    STOP
big:
    SMALL_IMMEDIATE 3
    STORE 42
    STOP
three:
    SMALL_IMMEDIATE 4
    STORE 43
    STOP
# expect var[40] = [1, 0, 0, 0]
# run event 0x7FFF
# expect var[40] = [1, 0, 3, 0]
# run event 0
# expect var[40] = [1, 2, 3, 0]
# expect pc 16
# run event 3
# expect var[40] = [1, 2, 3, 0]
# run event 1
# run event 0xFFFE
# expect var[40] = [1, 2, 3, 0]
# expect pc 16
# expect flags 0
