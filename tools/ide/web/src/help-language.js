// The Aseba language in brief, for the help panel: Aseba 1.6's language and
// the additions of this project's compiler (docs/language.md: locals,
// subroutines with parameters and a return value, calls in expressions).
// Each entry: a title, a few lines of code, and what to know.

/** @type {{ title: string, code: string, text: string }[]} */
export const LANGUAGE = [
    {
        title: "Variables and constants",
        code: "var speed = 300\nvar readings[8]\nvar gains[] = [1, 2, 3]\nreadings[2] = prox[2] * gains[0]",
        text: "Integers of 16 bits, scalars or arrays (indexed from 0; a[1:3] is a slice). A var is global, wherever it is written. Constants (the Constants tab) are named values known to every robot's script.",
    },
    {
        title: "Expressions",
        code: "x = (a + b) * 2 / c % 4\nx = abs(y) << 2 | mask\nx += 1\nx++",
        text: "+ - * / % (the sign of the dividend), << >> & | ^ ~, abs; comparisons == != < <= > >= and the words and, or, not in conditions. A division by zero or an index out of its array stops the robot: the IDE shows the line.",
    },
    {
        title: "Events",
        code: "onevent ir_sensors\n    leftSpeed = 500 - prox[0]\n\nonevent ping\n    emit pong args[0] + 1",
        text: "The code before the first onevent runs once, at load. onevent NAME runs at each event: the robot's own (Help: this robot's events) or the project's global events, whose arguments are in args. emit sends a global event to every robot and this IDE.",
    },
    {
        title: "Choices and loops",
        code: "if x > 10 then\n    y = 1\nelseif x < 0 then\n    y = -1\nelse\n    y = 0\nend\nwhen prox[0] > 2000 do\n    leds[0] = 1\nend\nwhile i < 8 do\n    i++\nend\nfor i in 0:7 step 2 do\n    sum += prox[i]\nend",
        text: "when runs its block once each time its condition becomes true. for counts from the first bound to the second, both included.",
    },
    {
        title: "Native functions",
        code: "call math.fill(readings, 0)\ncall math.max(x, a, b)",
        text: "The robot's functions, called with call (Help: this robot's natives; the Functions tab beside the editor).",
    },
    {
        title: "Local variables (this compiler)",
        code: "onevent ir_sensors\n    local front = prox[0] + prox[7]\n    if front > 1000 then\n        local turn = front / 4\n        leftSpeed = -turn\n    end",
        text: "A local exists from its declaration to the end of its block; handlers share the words of their locals, since they never run at the same time.",
    },
    {
        title: "Subroutines, parameters and values (this compiler)",
        code: "sub clamp(value, low, high)\n    if value < low then\n        return low\n    end\n    return value\n\nsub halt\n    leftSpeed = 0\n\nonevent ir_sensors\n    leftSpeed = clamp(prox[0] - prox[7], -500, 500)\n    callsub halt",
        text: "Parameters are copies (an array of fixed size: v[3]). A subroutine that returns a value returns one on every path; return is the last statement of its block. Subroutines may not call themselves. sub name without parentheses is Aseba 1.6's, called with callsub.",
    },
    {
        title: "Comments",
        code: "# to the end of the line\n#* over\n   several lines *#",
        text: "Ctrl+D comments the selected lines, Ctrl+Shift+D uncomments them.",
    },
];
