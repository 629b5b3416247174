// The page's entry point.
import "./style.css";

const app = document.getElementById("app");
const socket = new WebSocket(`ws://${location.host}/ws`);
socket.onmessage = (event) => {
    const message = JSON.parse(event.data);
    if (message.type === "hello")
        app.textContent = `${message.robots.length} robots`;
};
