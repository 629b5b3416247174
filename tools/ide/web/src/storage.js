// What the page keeps in the browser's localStorage: every robot's script
// (so that no text is lost when the server, the network or the page goes
// away), a few settings of the layout, and the projects opened last.

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

// Projects opened from this browser, newest first: [{name, content, time}].
const RECENT_PROJECTS = 5;
// A larger project is opened but not remembered: the storage is the scripts'.
export const MAX_RECENT_PROJECT_CHARACTERS = 256 * 1024;

export function loadRecentProjects() {
    const entries = read("recent-projects");
    return Array.isArray(entries)
        ? entries.filter((entry) => typeof entry?.name === "string" && typeof entry?.content === "string")
        : [];
}

export function rememberProject(name, content) {
    if (content.length > MAX_RECENT_PROJECT_CHARACTERS) return;
    const others = loadRecentProjects().filter((entry) => entry.name !== name);
    write("recent-projects", [{ name, content, time: Date.now() }, ...others].slice(0, RECENT_PROJECTS));
}
