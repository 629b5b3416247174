// The serial bootloader's core: the Aseba bootloader messages
// (protocol.md §6.9) over the board's link, writing application pages.
//
// Pages are BOOT_PAGE_WORDS flash words as the Aseba host counts them in a
// HEX file: there every word takes 4 bytes (on the e-puck a 24-bit
// instruction: low, middle, upper, then a zero phantom byte, at byte address
// 2 x PC), so a page is 128 bytes, page number = address / BOOT_PAGE_SPAN,
// and each 4-byte PAGE_DATA_WRITE chunk is one word. A page must be one
// erase unit of the chip (a row on the e-puck): a page of another size is
// refused.
//
// Only the pages of the application region (boot_application.h) can be
// written or read; what lies below it (on the e-puck the reset GOTO and
// vector tables), the bytecode store and the bootloaders above it are
// refused, so the bootloader never erases itself or the way to it. A page
// that already holds its data is not rewritten. Every page write but the descriptor's first erases
// the descriptor, so an interrupted flashing leaves no valid application and the bootloader stays.
//
// Usage: boot_start once after reset, then boot_poll in a loop until it
// says to start the application (the chip then jumps to the entry address
// that boot_application_valid gives).

#ifndef BOOTLOADER_H
#define BOOTLOADER_H

#include <stdbool.h>
#include <stdint.h>

#include "bootloader/boot_application.h"
#include "hal/hal.h"

#define BOOT_BYTES_PER_INSTRUCTION 4u // per word, in HEX files and PAGE_DATA_WRITE chunks
#define BOOT_PAGE_BYTES            (BOOT_PAGE_WORDS * BOOT_BYTES_PER_INSTRUCTION)
#define BOOT_PAGES_START           ((uint16_t)(BOOT_APPLICATION_START / BOOT_PAGE_SPAN))
#define BOOT_PAGES_COUNT                                                                           \
    ((uint16_t)((BOOT_APPLICATION_END - BOOT_APPLICATION_START) / BOOT_PAGE_SPAN))

// How long after reset the bootloader waits to be addressed before it starts
// a valid application, and the silence that abandons a half-received frame.
#define BOOT_WAIT_MS      1000u
#define BOOT_FRAME_GAP_MS 500u

// The message types of protocol.md §3 the bootloader uses.
#define BOOT_MESSAGE_RESET           0x8000u
#define BOOT_MESSAGE_READ_PAGE       0x8001u
#define BOOT_MESSAGE_WRITE_PAGE      0x8002u
#define BOOT_MESSAGE_PAGE_DATA_WRITE 0x8003u
#define BOOT_MESSAGE_DESCRIPTION     0x8004u
#define BOOT_MESSAGE_PAGE_DATA_READ  0x8005u
#define BOOT_MESSAGE_ACK             0x8006u
#define BOOT_MESSAGE_REBOOT          0xA00Eu

// BOOTLOADER_ACK error codes (protocol.md §5.15).
#define BOOT_ACK_SUCCESS            0u
#define BOOT_ACK_INVALID_FRAME_SIZE 1u
#define BOOT_ACK_PROGRAMMING_FAILED 2u // followed by the low 16 bits of the page's address
#define BOOT_ACK_NOT_PROGRAMMING    3u

#define BOOT_FRAME_HEADER_BYTES 6u // len, source, type
#define BOOT_PAYLOAD_KEPT_BYTES 8u // longer payloads are counted, not kept
#define BOOT_CHUNK_BYTES        4u // PAGE_DATA_WRITE / PAGE_DATA_READ data

typedef enum boot_status {
    BOOT_STAY,             // keep calling boot_poll
    BOOT_START_APPLICATION // the application is valid: jump to its entry
} boot_status;

typedef struct bootloader {
    hal_board *board;
    uint16_t node_id;
    uint32_t started_ms;
    bool waiting;               // no host has addressed us yet and BOOT_WAIT_MS has not passed
    uint32_t application_entry; // set when boot_poll returns BOOT_START_APPLICATION

    // The frame being received.
    uint8_t header[BOOT_FRAME_HEADER_BYTES];
    uint16_t header_fill;
    uint8_t payload[BOOT_PAYLOAD_KEPT_BYTES];
    uint16_t payload_fill; // bytes received, kept or not
    uint32_t last_byte_ms;

    // The page being programmed.
    bool programming;
    uint16_t page;
    uint16_t words_received;
    uint32_t page_words[BOOT_PAGE_WORDS];
} bootloader;

// Prepares the bootloader for node `node_id` and sends BOOTLOADER_DESCRIPTION.
void boot_start(bootloader *loader, hal_board *board, uint16_t node_id);

// Handles every byte the link has received; returns BOOT_START_APPLICATION
// after an acknowledged BOOTLOADER_RESET or, when no host addressed the
// bootloader, BOOT_WAIT_MS after boot_start, but only when the application
// is valid (boot_application_valid), its entry then in
// loader->application_entry.
boot_status boot_poll(bootloader *loader);

#endif
