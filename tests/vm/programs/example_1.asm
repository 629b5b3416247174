; bytecode.md §10.1 word for word: `count` at 36, `v` at 37..38, the timer
; is local event 0xFFFE. `init` sets v = [10, -3000]; each timer adds one to
; count; `when count > 5` emits alarm (event 0) with v once, when count
; first exceeds 5 (the branch is at address 11).
.raw
.word 0x0005 0xFFFE 0x0005 0xFFFF 0x0011
.word 0x3024 0x1001 0x8002 0x4024 0x3024 0x1005 0xA10C 0x0005 0xB000 0x0025 0x0002 0x0000
.word 0x1000 0x4024 0x100A 0x4025 0x2000 0xF448 0x4026 0x0000
# set var[36] = 77
# expect var[36] = [0, 10, -3000]
# expect flags 0
# expect pc 24
# run event 0xFFFE
# run event 0xFFFE
# run event 0xFFFE
# run event 0xFFFE
# run event 0xFFFE
# expect var[36] = 5
# expect no message
# expect bytecode[11] = 0xA10C
# run event 0xFFFE
# expect var[36] = 6
# expect emit 0 [10, -3000]
; the was-true bit (0x0200) is now set in the branch word
# expect bytecode[11] = 0xA30C
# run event 0xFFFE
# run event 0xFFFE
# expect var[36] = 8
# expect no message
# expect pc 16
# expect flags 0
