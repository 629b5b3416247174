// The serial bootloader's core: reads frames from the link byte by byte,
// answers the Aseba bootloader messages and programs application pages.

#include "bootloader/bootloader.h"

#define BYTE_BITS          8u
#define BYTE_MASK          0xFFu
#define WORD_BYTES         (HAL_FLASH_WORD_BITS / BYTE_BITS) // the bytes of a chunk stored
#define RECEIVE_CHUNK      16u
#define FRAME_MAX_PAYLOAD  6u // the largest payload the bootloader sends
#define DEST_BYTES         2u
#define PAGE_COMMAND_BYTES 4u // dest, page number
#define DATA_COMMAND_BYTES (DEST_BYTES + BOOT_CHUNK_BYTES)

static uint16_t get_u16(const uint8_t *bytes)
{
    return (uint16_t)(bytes[0] | ((uint16_t)bytes[1] << BYTE_BITS));
}

static void put_u16(uint8_t *bytes, uint16_t value)
{
    bytes[0] = (uint8_t)(value & BYTE_MASK);
    bytes[1] = (uint8_t)(value >> BYTE_BITS);
}

// --- sending -----------------------------------------------------------------

static void send_frame(bootloader *loader, uint16_t type, const uint8_t *payload, uint16_t length)
{
    uint8_t frame[BOOT_FRAME_HEADER_BYTES + FRAME_MAX_PAYLOAD];
    const uint8_t *next = frame;
    uint16_t left = (uint16_t)(BOOT_FRAME_HEADER_BYTES + length);
    uint16_t i;

    put_u16(frame, length);
    put_u16(frame + 2, loader->node_id);
    put_u16(frame + 4, type);
    for (i = 0; i < length; i++)
        frame[BOOT_FRAME_HEADER_BYTES + i] = payload[i];
    // The bootloader has nothing else to do: it waits for room.
    while (left > 0) {
        uint16_t taken = hal_link_send(loader->board, next, left);
        next += taken;
        left = (uint16_t)(left - taken);
        if (left > 0)
            hal_idle(loader->board);
    }
}

static void send_description(bootloader *loader)
{
    uint8_t payload[6];

    put_u16(payload, BOOT_PAGE_BYTES);
    put_u16(payload + 2, BOOT_PAGES_START);
    put_u16(payload + 4, BOOT_PAGES_COUNT);
    send_frame(loader, BOOT_MESSAGE_DESCRIPTION, payload, sizeof payload);
}

static void send_ack(bootloader *loader, uint16_t code)
{
    uint8_t payload[2];

    put_u16(payload, code);
    send_frame(loader, BOOT_MESSAGE_ACK, payload, sizeof payload);
}

// A failure ack carries the low 16 bits of the page's address.
static void send_failure(bootloader *loader, uint16_t page)
{
    uint8_t payload[4];

    put_u16(payload, BOOT_ACK_PROGRAMMING_FAILED);
    put_u16(payload + 2, (uint16_t)((uint32_t)page * BOOT_PAGE_SPAN));
    send_frame(loader, BOOT_MESSAGE_ACK, payload, sizeof payload);
}

// --- flash -------------------------------------------------------------------

static uint32_t page_address(uint16_t page)
{
    return (uint32_t)page * BOOT_PAGE_SPAN;
}

// Erases the unit under the page at `address`, which must be exactly the page.
static bool erase_page(hal_board *board, uint32_t address)
{
    uint32_t unit_start;

    return hal_flash_unit(board, address, &unit_start) == BOOT_PAGE_SPAN && unit_start == address &&
           hal_flash_erase(board, address);
}

static bool page_writable(uint16_t page)
{
    // Unsigned: a page below the start wraps to a large number.
    return (uint16_t)(page - BOOT_PAGES_START) < BOOT_PAGES_COUNT;
}

// Makes the application invalid before its pages change.
static bool erase_descriptor(hal_board *board)
{
    if (hal_flash_read(board, BOOT_DESCRIPTOR_ADDRESS) == HAL_FLASH_ERASED)
        return true;
    return erase_page(board, BOOT_DESCRIPTOR_ADDRESS);
}

static bool page_holds(bootloader *loader, uint32_t address)
{
    uint16_t i;

    for (i = 0; i < BOOT_PAGE_WORDS; i++) {
        if (hal_flash_read(loader->board, address + (uint32_t)i * HAL_FLASH_WORD_SPAN) !=
            loader->page_words[i])
            return false;
    }
    return true;
}

static bool program_page(bootloader *loader)
{
    uint32_t address = page_address(loader->page);

    // A page that already holds its data is left alone: re-flashing a
    // similar image wears less and is quicker.
    if (page_holds(loader, address))
        return true;
    if (!erase_page(loader->board, address) ||
        !hal_flash_program(loader->board, address, loader->page_words, BOOT_PAGE_WORDS))
        return false;
    return page_holds(loader, address);
}

// --- messages ----------------------------------------------------------------

static void write_page(bootloader *loader, uint16_t length)
{
    uint16_t page;

    loader->programming = false;
    if (length != PAGE_COMMAND_BYTES) {
        send_ack(loader, BOOT_ACK_INVALID_FRAME_SIZE);
        return;
    }
    page = get_u16(loader->payload + DEST_BYTES);
    if (!page_writable(page) ||
        (page_address(page) != BOOT_DESCRIPTOR_ADDRESS && !erase_descriptor(loader->board))) {
        send_failure(loader, page);
        return;
    }
    loader->programming = true;
    loader->page = page;
    loader->words_received = 0;
    send_ack(loader, BOOT_ACK_SUCCESS);
}

static void page_data_write(bootloader *loader, uint16_t length)
{
    const uint8_t *chunk = loader->payload + DEST_BYTES;
    uint32_t word = 0;
    uint16_t i;

    if (!loader->programming) {
        send_ack(loader, BOOT_ACK_NOT_PROGRAMMING);
        return;
    }
    if (length != DATA_COMMAND_BYTES) {
        loader->programming = false;
        send_ack(loader, BOOT_ACK_INVALID_FRAME_SIZE);
        return;
    }
    // The bytes beyond the word's (the dsPIC's phantom byte) are not stored.
    for (i = 0; i < WORD_BYTES; i++)
        word |= (uint32_t)chunk[i] << (BYTE_BITS * i);
    loader->page_words[loader->words_received++] = word;
    if (loader->words_received < BOOT_PAGE_WORDS)
        return;
    loader->programming = false;
    if (program_page(loader))
        send_ack(loader, BOOT_ACK_SUCCESS);
    else
        send_failure(loader, loader->page);
}

static void read_page(bootloader *loader, uint16_t length)
{
    uint16_t page;
    uint16_t i;
    uint16_t byte;

    if (length != PAGE_COMMAND_BYTES) {
        send_ack(loader, BOOT_ACK_INVALID_FRAME_SIZE);
        return;
    }
    page = get_u16(loader->payload + DEST_BYTES);
    if (!page_writable(page)) {
        send_failure(loader, page);
        return;
    }
    for (i = 0; i < BOOT_PAGE_WORDS; i++) {
        uint32_t word =
          hal_flash_read(loader->board, page_address(page) + (uint32_t)i * HAL_FLASH_WORD_SPAN);
        uint8_t chunk[BOOT_CHUNK_BYTES];
        for (byte = 0; byte < BOOT_CHUNK_BYTES; byte++)
            chunk[byte] =
              byte < WORD_BYTES ? (uint8_t)((word >> (BYTE_BITS * byte)) & BYTE_MASK) : 0;
        send_frame(loader, BOOT_MESSAGE_PAGE_DATA_READ, chunk, BOOT_CHUNK_BYTES);
    }
    send_ack(loader, BOOT_ACK_SUCCESS);
}

// Handles the frame now complete; returns whether to start the application.
static bool handle_frame(bootloader *loader)
{
    uint16_t length = get_u16(loader->header);
    uint16_t type = get_u16(loader->header + 4);

    if (type != BOOT_MESSAGE_RESET && type != BOOT_MESSAGE_READ_PAGE &&
        type != BOOT_MESSAGE_WRITE_PAGE && type != BOOT_MESSAGE_PAGE_DATA_WRITE &&
        type != BOOT_MESSAGE_REBOOT)
        return false;
    if (length < DEST_BYTES || get_u16(loader->payload) != loader->node_id)
        return false;
    loader->waiting = false; // a host talks to us: stay until it says otherwise
    switch (type) {
    case BOOT_MESSAGE_RESET:
        send_ack(loader, BOOT_ACK_SUCCESS);
        if (boot_application_valid(loader->board, &loader->application_entry))
            return true;
        send_description(loader); // no valid application: still here
        break;
    case BOOT_MESSAGE_REBOOT: // the host expects a fresh description
        send_description(loader);
        break;
    case BOOT_MESSAGE_WRITE_PAGE: write_page(loader, length); break;
    case BOOT_MESSAGE_PAGE_DATA_WRITE: page_data_write(loader, length); break;
    default: read_page(loader, length); break;
    }
    return false;
}

// Takes one received byte; returns whether to start the application.
static bool receive_byte(bootloader *loader, uint8_t byte)
{
    if (loader->header_fill < BOOT_FRAME_HEADER_BYTES) {
        loader->header[loader->header_fill++] = byte;
        if (loader->header_fill < BOOT_FRAME_HEADER_BYTES || get_u16(loader->header) > 0)
            return false;
    } else {
        if (loader->payload_fill < BOOT_PAYLOAD_KEPT_BYTES)
            loader->payload[loader->payload_fill] = byte;
        loader->payload_fill++;
        if (loader->payload_fill < get_u16(loader->header))
            return false;
    }
    loader->header_fill = 0;
    loader->payload_fill = 0;
    return handle_frame(loader);
}

// --- main loop ---------------------------------------------------------------

void boot_start(bootloader *loader, hal_board *board, uint16_t node_id)
{
    loader->board = board;
    loader->node_id = node_id;
    loader->started_ms = hal_milliseconds(board);
    loader->waiting = true;
    loader->application_entry = 0;
    loader->header_fill = 0;
    loader->payload_fill = 0;
    loader->last_byte_ms = loader->started_ms;
    loader->programming = false;
    loader->page = 0;
    loader->words_received = 0;
    send_description(loader);
}

boot_status boot_poll(bootloader *loader)
{
    uint8_t bytes[RECEIVE_CHUNK];
    uint16_t count;
    uint16_t i;
    uint32_t now = hal_milliseconds(loader->board);

    if (loader->header_fill > 0 && now - loader->last_byte_ms > BOOT_FRAME_GAP_MS) {
        loader->header_fill = 0; // a sender gave up in the middle of a frame
        loader->payload_fill = 0;
    }
    while ((count = hal_link_receive(loader->board, bytes, RECEIVE_CHUNK)) > 0) {
        loader->last_byte_ms = now;
        for (i = 0; i < count; i++) {
            if (receive_byte(loader, bytes[i]))
                return BOOT_START_APPLICATION;
        }
    }
    if (loader->waiting && now - loader->started_ms >= BOOT_WAIT_MS) {
        loader->waiting = false; // decide once: an invalid application keeps us here
        if (boot_application_valid(loader->board, &loader->application_entry))
            return BOOT_START_APPLICATION;
    }
    return BOOT_STAY;
}
