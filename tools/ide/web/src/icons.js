// The page's icons: SVG paths on a 24 × 24 grid, drawn with the text colour.

export const icons = {
    load: "M11 16V7.8L7.4 11.4 6 10l6-6 6 6-1.4 1.4L13 7.8V16zM5 18h14v2H5z",
    run: "M8 5v14l11-7z",
    pause: "M6 5h4v14H6zM14 5h4v14h-4z",
    step: "M5 5v14l9-7zM16 5h3v14h-3z",
    stop: "M6 6h12v12H6z",
    reset: "M12 5V2L7 6l5 4V7a5 5 0 1 1-5 5H5a7 7 0 1 0 7-7z",
    store: "M5 3h11l3 3v15H5zM8 5v4h7V5zM8 13v6h8v-6z",
    reboot: "M11 3h2v9h-2zM7.05 6.05l1.41 1.41A5 5 0 1 0 15.54 7.46l1.41-1.41A7 7 0 1 1 7.05 6.05z",
    open: "M3 5h6l2 2h10v12H3zM5 9v8h14V9z",
    save: "M5 3h11l3 3v15H5zM8 5v4h7V5zM8 13v6h8v-6z",
    download: "M11 4h2v8.2l3.6-3.6L18 10l-6 6-6-6 1.4-1.4 3.6 3.6zM5 18h14v2H5z",
    binary: "M6 2h8l4 4v16H6zM8 4v16h8V8h-4V4zM9 11h2v6H9zM13 11h2v6h-2z",
    find: "M10 4a6 6 0 1 0 3.7 10.7l4.6 4.6 1.4-1.4-4.6-4.6A6 6 0 0 0 10 4zm0 2a4 4 0 1 1 0 8 4 4 0 0 1 0-8z",
    gotoLine: "M4 5h10v2H4zM4 11h7v2H4zM4 17h10v2H4zM15 8l5 4-5 4z",
    close: "M6.4 5 12 10.6 17.6 5 19 6.4 13.4 12 19 17.6 17.6 19 12 13.4 6.4 19 5 17.6 10.6 12 5 6.4z",
    add: "M11 5h2v6h6v2h-6v6h-2v-6H5v-2h6z",
    clear: "M9 3h6l1 2h4v2H4V5h4zM6 8h12l-1 13H7z",
    send: "M3 20l18-8L3 4v6l12 2-12 2z",
    expand: "M9 6l6 6-6 6z",
    collapse: "M6 9l6 6 6-6z",
};
