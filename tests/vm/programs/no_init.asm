; Without an `init` entry the upload leaves the VM stopped and idle with
; nothing to run (§6.4); other events still run once RUN was sent.
# trace states
event 0 handler
handler:
    SMALL_IMMEDIATE 1
    STORE 40
    STOP                ; at 5
; the implicit start sent SET_BYTECODE (pc 0 is stale, flags 2) then RUN
# expect state pc=0 flags=2
# expect state pc=0 flags=0
# expect var[40] = 0
# run event 0
# expect var[40] = 1
# expect pc 5
# expect flags 0
