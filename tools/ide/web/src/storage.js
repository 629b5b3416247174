// What the page keeps in the browser's localStorage: every robot's script
// (so that no text is lost when the server, the network or the page goes
// away) and a few settings of the layout.

const PREFIX = "aseba-ide/";

function read(key) {
    try {
        const text = localStorage.getItem(PREFIX + key);
        return text === null ? null : JSON.parse(text);
    } catch {
        return null;
    }
}

// False when the browser refused (storage full or disabled).
function write(key, value) {
    try {
        localStorage.setItem(PREFIX + key, JSON.stringify(value));
        return true;
    } catch {
        return false;
    }
}

// {text, synced} or null; `synced` says whether the server had this text.
export function loadScript(robot) {
    const entry = read(`script/${robot}`);
    return entry && typeof entry.text === "string" ? entry : null;
}

export function saveScript(robot, text, synced) {
    return write(`script/${robot}`, { text, synced, time: Date.now() });
}

export function loadSetting(name, fallback) {
    return read(`setting/${name}`) ?? fallback;
}

export function saveSetting(name, value) {
    write(`setting/${name}`, value);
}
