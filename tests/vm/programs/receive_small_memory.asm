; With fewer variables than the args size declares, the copy stops at the
; end of the variables (§8.5: no access outside them).
# memory variables=4 args=32
event 0 handler
handler:
    STOP
# receive 0 source 8 [1, 2, 3, 4, 5, 6]
# expect var[0] = [0, 8, 1, 2]
