; Incoming user events (§7): V[1] = source, min(payload, args size) words
; copied to V[2 ...] (args size 4 here; the rest of args keeps its value),
; copied even when the event is not handled; dropped altogether while a
; handler is paused (STEP_BY_STEP and EVENT_ACTIVE).
# memory args=4
# budget 50
event 0 sum
event 1 endless
sum:
    LOAD 2
    LOAD 5
    BINARY_ARITHMETIC ADD
    STORE 40
    STOP
endless:
    JUMP endless        ; at 10
# set var[6] = 66
# receive 0 source 7 [10, 20, 30, 40, 50, 60]
# expect var[1] = 7
# expect var[2] = [10, 20, 30, 40, 66]
# expect var[40] = 50
# receive 2 source 9 [-1]
# expect var[1] = 9
# expect var[2] = [-1, 20, 30, 40, 66]
# receive 0 source 3 []
# expect var[1] = 3
# expect var[2] = [-1, 20, 30, 40, 66]
# expect var[40] = 39
; paused inside an event: the next event is dropped, source and args too
# receive 1 source 4 [1]
# expect flags 1
# pause
# receive 0 source 5 [2, 2, 2, 2]
# expect var[1] = 4
# expect var[2] = [1, 20, 30, 40]
# expect flags 3
# expect pc 10
# expect var[40] = 39
; once running again, a new event kills the endless handler
# continue
# receive 0 source 5 [2, 2, 2, 2]
# expect killed pc=10
# expect var[40] = 4
