; NATIVE_CALL f calls entry f of the node's table; the native pops its own
; arguments, the first popped being the top of the stack (bytecode.md §9),
; and pc moves on by one. Native 0 of the harness: V[dest] = V[a] - V[b],
; popped in the order dest, a, b.
event init start
start:
    SMALL_IMMEDIATE 42  ; &b, pushed first
    SMALL_IMMEDIATE 41  ; &a
    SMALL_IMMEDIATE 40  ; &dest, top of the stack
    NATIVE_CALL 0       ; at 6
    SMALL_IMMEDIATE 9   ; the call left this below: it stays on the stack
    SMALL_IMMEDIATE 41
    SMALL_IMMEDIATE 42
    SMALL_IMMEDIATE 43
    NATIVE_CALL 0       ; V[43] = V[42] - V[41]
    STORE 44            ; the 9
    STOP
# set var[41] = [100, 30]
# expect var[40] = [70, 100, 30, -70, 9]
# expect sp -1
# expect flags 0
