; SUB_CALL to an address beyond the bytecode and SUB_RET to one (or to a
; negative value, i.e. a large uint16) stop the VM with "out of bytecode
; bounds" (bytecode.md §8.5); the pc reported is left open by the spec.
# memory bytecode=64
event init call_far
event 0 return_far
event 1 return_negative
event 2 return_to_self
call_far:
    SUB_CALL 4095       ; at 9
return_far:
    SMALL_IMMEDIATE 64  ; at 10
    SUB_RET
return_negative:
    SMALL_IMMEDIATE -1  ; at 12
    SUB_RET
return_to_self:
    SMALL_IMMEDIATE 17  ; at 14: returns to 17, a STOP
    SUB_RET
    SMALL_IMMEDIATE 1
    STOP
# expect error node_specific pc=* "out of bytecode bounds"
# expect flags 2
# run event 0
# continue
# expect error node_specific pc=* "out of bytecode bounds"
# expect flags 2
# run event 1
# continue
# expect error node_specific pc=* "out of bytecode bounds"
# expect flags 2
# run event 2
# continue
# expect flags 0
# expect pc 17
# expect sp -1
