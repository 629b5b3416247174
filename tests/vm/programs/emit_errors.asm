; EMIT of more than 258 words (§7) or of words outside the variables (§8.5)
; stops the VM without sending anything; the texts are left open by the spec.
# memory variables=300
event init too_large
event 0 outside
event 1 outside_start
event 2 wrapping
too_large:
    EMIT 1 0 259        ; at 9
    STOP
outside:
    EMIT 1 290 11       ; at 13: 290 + 11 > 300
    STOP
outside_start:
    EMIT 1 300 1        ; at 17
    STOP
wrapping:
    EMIT 1 0xFFFF 2     ; at 21: the end wraps around 16 bits
    STOP
# expect error node_specific pc=9
# expect flags 2
# run event 0
# continue
# expect error node_specific pc=13 "out of variables bounds"
# run event 1
# continue
# expect error node_specific pc=17 "out of variables bounds"
# run event 2
# continue
# expect error node_specific pc=21 "out of variables bounds"
# expect flags 2
