; bytecode.md §10.2 word for word: buf 36..39, i 40, m 41, the temporary at
; 1059. Native 11 and native 1 of the harness have the stack contracts of
; math.stat and math.fill (tests/support/vm_harness.hpp): stat writes min,
; max then mean (sum / size) into m, fill copies V[value] into buf.
.raw
.word 0x0003 0x0000 0x0003
.word 0x3002 0x1003 0x8005 0x3028 0x6024 0x0004 0x3028 0x1001 0x8002 0x1004 0x8006 0x4028
.word 0x1004 0x1029 0x1029 0x1029 0x1024 0xC00B 0xD017 0x0000
.word 0x1004 0x1000 0x4423 0x1423 0x1024 0xC001 0xE000
# memory variables=1060 bytecode=512 stack=64
# set var[36] = [1, 2, 3, 4, 3, 5]
# set var[1059] = 9
; ping with args[0] = 30: buf[3] = 10 -> buf = [1, 2, 3, 10], i = (3 + 1) % 4 = 0,
; m = (1 + 2 + 3 + 10) / 4 = 4, then clear fills buf with the temporary 0.
# receive 0 source 5 [30]
# expect var[1] = 5
# expect var[2] = 30
# expect var[36] = [0, 0, 0, 0, 0, 4]
# expect var[1059] = 0
# expect flags 0
# expect pc 22
# expect sp -1
; args[0] = -31: buf[0] = -10, i = 1, m = -10 / 4 = -2 (truncated)
# receive 0 source 6 [-31]
# expect var[36] = [0, 0, 0, 0, 1, -2]
