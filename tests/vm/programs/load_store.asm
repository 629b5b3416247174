; LOAD pushes V[a], STORE pops into V[a], on the first and the last variable.
event init start
start:
    LOAD 63
    STORE 0
    LOAD 40
    STORE 63
    LOAD 0
    LOAD 63
    STORE 41
    STORE 42
    STOP
# set var[40] = -5
# set var[63] = 1234
# expect var[0] = 1234
# expect var[63] = -5
# expect var[41] = [-5, 1234]
# expect sp -1
