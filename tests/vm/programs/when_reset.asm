; The reset-when-flags pass (§5.1) clears the was-true bit of every branch,
; walking from B[0], the first code word, instruction by instruction. The
; image is uploaded with was-true bits already set. Upstream starts the walk
; at 2 * B[0] + 1 = 7 and so misses the `when` at 5 (§11): ours must not.
; An operand word that looks like a branch (0xA30C) must be left alone,
; which it is only if the walk follows the instruction lengths.
event 0 handler
handler:
    LOAD 2                                              ; at 3
    SMALL_IMMEDIATE 0
    CONDITIONAL_BRANCH BIGGER_THAN skip when was_true   ; at 5
    LOAD 40
    SMALL_IMMEDIATE 1
    BINARY_ARITHMETIC ADD
    STORE 40
skip:
    LARGE_IMMEDIATE 0xA30C                              ; at 11, its operand at 12
    STORE 42
    EMIT 0xA30 0 0
    LOAD 2
    SMALL_IMMEDIATE 0
    CONDITIONAL_BRANCH BIGGER_THAN plain was_true       ; at 19, an `if`: was-true ignored
    LOAD 41
    SMALL_IMMEDIATE 1
    BINARY_ARITHMETIC ADD
    STORE 41
plain:
    LOAD 2
    SMALL_IMMEDIATE 0
    CONDITIONAL_BRANCH BIGGER_THAN done when was_true   ; at 27
    LOAD 43
    SMALL_IMMEDIATE 1
    BINARY_ARITHMETIC ADD
    STORE 43
done:
    STOP
; after the upload (a RESET), both `when` words are cleared
# expect bytecode[5] = 0xA10C
# expect bytecode[27] = 0xA10C
# expect bytecode[12] = 0xA30C
# receive 0 source 1 [1]
# expect emit 2608 []
# expect var[40] = [1, 1, 0xA30C, 1]
# receive 0 source 1 [1]
# expect emit 2608 []
# expect var[40] = [1, 2, 0xA30C, 1]
# expect bytecode[5] = 0xA30C
# reset
# expect bytecode[5] = 0xA10C
# expect bytecode[27] = 0xA10C
# expect bytecode[19] = 0xA00C
# receive 0 source 1 [1]
# expect emit 2608 []
# expect var[40] = [2, 3, 0xA30C, 2]
