// A robot's memory as a file: every variable the page knows by name, with
// the values last read, exported as JSON and written back to a robot from
// such a file. Only the variables of the same name and size are written:
// a file from another program or robot writes what they share.

import { parseIntegers } from "./format.js";

export const MEMORY_FORMAT = "aseba-ide robot memory 1";

/**
 * The file's content for `robot` (the server's robot object) and its
 * variables' values from address 0.
 * @param {{ robot: string, id: number, name: string, variables?: { name: string, address: number, size: number }[] }} robot
 * @param {string} label how people see the robot
 * @param {number[]} values
 */
export function memoryFile(robot, label, values) {
    const variables = (robot.variables ?? []).map(({ name, address, size }) => ({
        name,
        values: values.slice(address, address + size),
    }));
    return `${JSON.stringify({ format: MEMORY_FORMAT, robot: label, node: robot.id, variables }, null, 1)}\n`;
}

/**
 * What a memory file writes to `robot`: [{name, values}], and the names it
 * leaves (unknown to the robot, or of another size). Throws an Error that
 * says why the text is not such a file.
 * @param {{ variables?: { name: string, size: number }[] }} robot
 * @param {string} text
 */
export function memoryWrites(robot, text) {
    let file;
    try {
        file = JSON.parse(text);
    } catch {
        throw new Error("it is not JSON");
    }
    if (file?.format !== MEMORY_FORMAT || !Array.isArray(file.variables))
        throw new Error("it is not a robot's memory saved by this IDE");
    const sizes = new Map((robot.variables ?? []).map((variable) => [variable.name, variable.size]));
    const writes = [];
    const left = [];
    for (const entry of file.variables) {
        const values = Array.isArray(entry?.values) ? parseIntegers(entry.values.join(",")) : [];
        if (sizes.get(entry?.name) === values.length && values.length > 0) writes.push({ name: entry.name, values });
        else left.push(String(entry?.name));
    }
    return { writes, left };
}
