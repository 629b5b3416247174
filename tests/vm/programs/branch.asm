; CONDITIONAL_BRANCH: true falls through (pc + 2), false jumps by the
; displacement relative to the branch; a backward branch and JUMPs make a
; loop: sum of 1..10 = 55, with an `if` inside counting the even numbers.
event init start
start:
    SMALL_IMMEDIATE 0
    STORE 40            ; i
    SMALL_IMMEDIATE 0
    STORE 41            ; sum
    SMALL_IMMEDIATE 0
    STORE 42            ; evens
loop:
    LOAD 40
    SMALL_IMMEDIATE 10
    CONDITIONAL_BRANCH SMALLER_THAN done
    LOAD 40
    SMALL_IMMEDIATE 1
    BINARY_ARITHMETIC ADD
    STORE 40
    LOAD 41
    LOAD 40
    BINARY_ARITHMETIC ADD
    STORE 41
    LOAD 40
    SMALL_IMMEDIATE 1
    BINARY_ARITHMETIC BIT_AND
    SMALL_IMMEDIATE 0
    CONDITIONAL_BRANCH EQUAL odd
    LOAD 42
    SMALL_IMMEDIATE 1
    BINARY_ARITHMETIC ADD
    STORE 42
odd:
    JUMP loop
done:
    STOP
# expect var[40] = [10, 55, 5]
# expect flags 0
