; `when`: the true block runs only when the condition becomes true after
; having been false, or on its first true evaluation after a reset (§5).
; Event 0 compares args[0] > 0 and counts the runs of the true block in
; V[40]; an `if` on the same condition counts every true evaluation in V[41].
event 0 handler
handler:
    LOAD 2
    SMALL_IMMEDIATE 0
    CONDITIONAL_BRANCH BIGGER_THAN after_when when     ; at 5
    LOAD 40
    SMALL_IMMEDIATE 1
    BINARY_ARITHMETIC ADD
    STORE 40
after_when:
    LOAD 2
    SMALL_IMMEDIATE 0
    CONDITIONAL_BRANCH BIGGER_THAN done               ; at 13
    LOAD 41
    SMALL_IMMEDIATE 1
    BINARY_ARITHMETIC ADD
    STORE 41
done:
    STOP
# receive 0 source 1 [1]
# expect var[40] = [1, 1]
# expect bytecode[5] = 0xA30C
# expect bytecode[13] = 0xA20C
# receive 0 source 1 [5]
# receive 0 source 1 [7]
# expect var[40] = [1, 3]
# receive 0 source 1 [0]
# expect var[40] = [1, 3]
# expect bytecode[5] = 0xA10C
# expect bytecode[13] = 0xA00C
# receive 0 source 1 [-4]
# receive 0 source 1 [2]
# expect var[40] = [2, 4]
; a reset clears the was-true bits: the next true evaluation runs the block
# reset
# expect bytecode[5] = 0xA10C
# receive 0 source 1 [3]
# expect var[40] = [3, 5]
# receive 0 source 1 [3]
# expect var[40] = [3, 6]
