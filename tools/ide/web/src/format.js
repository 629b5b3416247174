// Formats shared by the views and the CSV exports.

function pad(value, width = 2) {
    return String(value).padStart(width, "0");
}

// "14:03:07.250", local time.
export function clockTime(milliseconds) {
    const date = new Date(milliseconds);
    return `${pad(date.getHours())}:${pad(date.getMinutes())}:${pad(date.getSeconds())}.${pad(date.getMilliseconds(), 3)}`;
}

// One CSV line per row, fields quoted when they need it (RFC 4180).
export function csv(rows) {
    return (
        rows
            .map((row) =>
                row
                    .map((field) => {
                        const text = field === null || field === undefined ? "" : String(field);
                        return /[",\r\n]/.test(text) ? `"${text.replaceAll('"', '""')}"` : text;
                    })
                    .join(","),
            )
            .join("\r\n") + "\r\n"
    );
}

// "aseba-events-2024-05-01T14-03-07.csv"
export function stampedFileName(prefix, extension) {
    const stamp = new Date().toISOString().slice(0, 19).replaceAll(":", "-");
    return `${prefix}-${stamp}.${extension}`;
}

// Integers typed by a person: "1, -2 0x10".
export function parseIntegers(text) {
    const parts = text.split(/[\s,;]+/).filter(Boolean);
    return parts.map((part) => {
        if (!/^[-+]?(\d+|0x[0-9a-f]+|0b[01]+)$/i.test(part)) throw new Error(`"${part}" is not an integer`);
        const negative = part.startsWith("-");
        const digits = part.replace(/^[-+]/, "");
        let value = /^0x/i.test(digits)
            ? parseInt(digits.slice(2), 16)
            : /^0b/i.test(digits)
              ? parseInt(digits.slice(2), 2)
              : parseInt(digits, 10);
        if (negative) value = -value;
        if (value < -32768 || value > 65535) throw new Error(`${part} is out of the 16-bit range`);
        return value > 32767 ? value - 65536 : value;
    });
}
