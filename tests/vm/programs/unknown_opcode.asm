; Opcode 0xF stops the VM with NODE_SPECIFIC_ERROR "unknown bytecode"
; (bytecode.md §5, §11: upstream would spin), pc on the word.
event init start
start:
    SMALL_IMMEDIATE 1
    STORE 40
    .word 0xF000        ; at 7
    SMALL_IMMEDIATE 2
    STORE 40
    STOP
event 0 other
other:
    .word 0xFFFF        ; at 11
# expect error node_specific pc=7 "unknown bytecode"
# expect var[40] = 1
# expect pc 7
# expect flags 2
# run event 0
# continue
# expect error node_specific pc=11 "unknown bytecode"
