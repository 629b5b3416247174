// Two-slot records in program flash: see bytecode_store.h for the format and
// why a power cut can never lose both the old and the new record.

#include "store/bytecode_store.h"

#include "vm/node_crc.h"

#define BYTE_BITS            8u
#define BYTE_MASK            0xFFu
#define HEADER_MAGIC         0u // byte offsets in the header
#define HEADER_SEQUENCE      2u
#define HEADER_COUNT         4u
#define HEADER_CRC           6u
#define HEADER_CHECKED_BYTES 6u // magic, sequence, count: covered by the CRC
#define NO_SLOT              0xFFFFu

typedef char
  settings_fit_their_slot[STORE_SETTINGS_CAPACITY_WORDS >= STORE_SETTINGS_WORDS ? 1 : -1];
#define FIRST_SEQUENCE 1u

static uint32_t block_address(const store_place *place, uint16_t slot, uint16_t block)
{
    return place->slot_address[slot] + (uint32_t)block * STORE_BLOCK_SPAN;
}

// Byte `position` of a slot's stream: STORE_BYTES_PER_WORD per flash word,
// low byte first.
static uint8_t read_byte(hal_board *board, uint32_t slot_address, uint16_t position)
{
    uint16_t word = (uint16_t)(position / STORE_BYTES_PER_WORD);
    uint16_t byte = (uint16_t)(position % STORE_BYTES_PER_WORD);
    uint32_t value = hal_flash_read(board, slot_address + (uint32_t)word * HAL_FLASH_WORD_SPAN);

    return (uint8_t)((value >> (BYTE_BITS * byte)) & BYTE_MASK);
}

static uint16_t read_word(hal_board *board, uint32_t slot_address, uint16_t position)
{
    uint16_t low = read_byte(board, slot_address, position);
    uint16_t high = read_byte(board, slot_address, (uint16_t)(position + 1u));

    return (uint16_t)(low | (uint16_t)(high << BYTE_BITS));
}

uint16_t store_capacity(const store_place *place)
{
    return (uint16_t)STORE_CAPACITY_WORDS(place->slot_blocks);
}

bool store_slot_valid(hal_board *board,
                      const store_place *place,
                      uint16_t slot,
                      store_slot_header *header)
{
    uint32_t base = place->slot_address[slot];
    uint16_t count = read_word(board, base, HEADER_COUNT);
    uint16_t end;
    uint16_t crc = 0;
    uint16_t position;

    if (read_word(board, base, HEADER_MAGIC) != place->magic || count > store_capacity(place))
        return false;
    end = (uint16_t)(STORE_HEADER_BYTES + count * STORE_WORD_BYTES);
    for (position = 0; position < end; position++) {
        uint8_t byte;
        if (position >= HEADER_CHECKED_BYTES && position < STORE_HEADER_BYTES)
            continue; // the CRC does not cover itself
        byte = read_byte(board, base, position);
        crc = node_crc16(crc, &byte, 1);
    }
    if (crc != read_word(board, base, HEADER_CRC))
        return false;
    header->sequence = read_word(board, base, HEADER_SEQUENCE);
    header->count = count;
    return true;
}

// Whether sequence `a` was written after `b`, across the wrap from 0xFFFF
// to 0: the two slots are never more than 2^15 saves apart.
static bool newer(uint16_t a, uint16_t b)
{
    return (int16_t)(uint16_t)(a - b) > 0;
}

// The valid slot with the newest sequence number, or NO_SLOT.
static uint16_t newest_slot(hal_board *board, const store_place *place, store_slot_header *newest)
{
    uint16_t found = NO_SLOT;
    uint16_t slot;

    for (slot = 0; slot < STORE_SLOT_COUNT; slot++) {
        store_slot_header header;
        if (!store_slot_valid(board, place, slot, &header))
            continue;
        if (found == NO_SLOT || newer(header.sequence, newest->sequence)) {
            found = slot;
            *newest = header;
        }
    }
    return found;
}

// Byte `position` of the record being written: the header, then the words.
static uint8_t record_byte(const uint8_t *header, const uint16_t *words, uint16_t position)
{
    uint16_t word;

    if (position < STORE_HEADER_BYTES)
        return header[position];
    word = words[(position - STORE_HEADER_BYTES) / STORE_WORD_BYTES];
    if ((position - STORE_HEADER_BYTES) % STORE_WORD_BYTES == 0)
        return (uint8_t)(word & BYTE_MASK);
    return (uint8_t)(word >> BYTE_BITS);
}

static void put_word(uint8_t *bytes, uint16_t value)
{
    bytes[0] = (uint8_t)(value & BYTE_MASK);
    bytes[1] = (uint8_t)(value >> BYTE_BITS);
}

// Programs block `block` of the stream (padding with erased bytes) and
// reads it back; returns false when the flash refuses or keeps other values.
static bool write_block(hal_board *board,
                        uint32_t address,
                        uint16_t block,
                        const uint8_t *header,
                        const uint16_t *words,
                        uint16_t end)
{
    uint32_t values[STORE_BLOCK_WORDS];
    uint16_t position = (uint16_t)(block * STORE_BLOCK_BYTES);
    uint16_t i;
    uint16_t byte;

    for (i = 0; i < STORE_BLOCK_WORDS; i++) {
        uint32_t value = 0;
        for (byte = 0; byte < STORE_BYTES_PER_WORD; byte++, position++) {
            uint32_t part = position < end ? record_byte(header, words, position) : BYTE_MASK;
            value |= part << (BYTE_BITS * byte);
        }
        values[i] = value;
    }
    if (!hal_flash_program(board, address, values, STORE_BLOCK_WORDS))
        return false;
    for (i = 0; i < STORE_BLOCK_WORDS; i++) {
        if (hal_flash_read(board, address + (uint32_t)i * HAL_FLASH_WORD_SPAN) != values[i])
            return false;
    }
    return true;
}

// Erases the units under the first `blocks` blocks of slot `slot`, in order;
// false when the slot does not own them (a unit begins before the slot or
// reaches past it) or an erase fails.
static bool erase_blocks(hal_board *board, const store_place *place, uint16_t slot, uint16_t blocks)
{
    uint32_t address = place->slot_address[slot];
    uint32_t end = block_address(place, slot, blocks);
    uint32_t slot_end = block_address(place, slot, place->slot_blocks);

    while (address < end) {
        uint32_t unit_start;
        uint32_t span = hal_flash_unit(board, address, &unit_start);
        if (span == 0 || unit_start != address || span > slot_end - address ||
            !hal_flash_erase(board, address))
            return false;
        address += span;
    }
    return true;
}

bool store_save(hal_board *board, const store_place *place, const uint16_t *words, uint16_t count)
{
    store_slot_header newest;
    uint16_t current = newest_slot(board, place, &newest);
    uint16_t target = current == 0 ? 1u : 0u;
    uint16_t sequence = current == NO_SLOT ? FIRST_SEQUENCE : (uint16_t)(newest.sequence + 1u);
    uint8_t header[STORE_HEADER_BYTES];
    uint16_t end;
    uint16_t blocks;
    uint16_t block;
    uint16_t position;
    uint16_t crc;

    if (count > store_capacity(place))
        return false;
    end = (uint16_t)(STORE_HEADER_BYTES + count * STORE_WORD_BYTES);
    blocks = (uint16_t)STORE_BLOCKS_FOR_WORDS(count);

    put_word(header + HEADER_MAGIC, place->magic);
    put_word(header + HEADER_SEQUENCE, sequence);
    put_word(header + HEADER_COUNT, count);
    crc = node_crc16(0, header, HEADER_CHECKED_BYTES);
    for (position = STORE_HEADER_BYTES; position < end; position++) {
        uint8_t byte = record_byte(header, words, position);
        crc = node_crc16(crc, &byte, 1);
    }
    put_word(header + HEADER_CRC, crc);

    // The header's block goes first when erasing and last when writing, so
    // that the slot reads as invalid for the whole save.
    if (!erase_blocks(board, place, target, blocks))
        return false;
    for (block = blocks; block-- > 0;) {
        if (!write_block(board, block_address(place, target, block), block, header, words, end))
            return false;
    }
    return store_slot_valid(board, place, target, &newest);
}

bool store_load(hal_board *board,
                const store_place *place,
                uint16_t *words,
                uint16_t capacity,
                uint16_t *count)
{
    store_slot_header newest;
    uint16_t slot = newest_slot(board, place, &newest);
    uint16_t i;

    if (slot == NO_SLOT || newest.count > capacity)
        return false;
    for (i = 0; i < newest.count; i++)
        words[i] = read_word(
          board, place->slot_address[slot], (uint16_t)(STORE_HEADER_BYTES + i * STORE_WORD_BYTES));
    *count = newest.count;
    return true;
}

void store_bytecode_place(store_place *place)
{
    place->slot_address[0] = STORE_BYTECODE_SLOT_0;
    place->slot_address[1] = STORE_BYTECODE_SLOT_1;
    place->slot_blocks = STORE_BYTECODE_SLOT_BLOCKS;
    place->magic = STORE_MAGIC_BYTECODE;
}

void store_settings_place(store_place *place)
{
    place->slot_address[0] = STORE_SETTINGS_SLOT_0;
    place->slot_address[1] = STORE_SETTINGS_SLOT_1;
    place->slot_blocks = STORE_SETTINGS_SLOT_BLOCKS;
    place->magic = STORE_MAGIC_SETTINGS;
}

bool store_save_bytecode(hal_board *board, const uint16_t *bytecode, uint16_t count)
{
    store_place place;

    store_bytecode_place(&place);
    return store_save(board, &place, bytecode, count);
}

bool store_load_bytecode(hal_board *board, uint16_t *bytecode, uint16_t capacity, uint16_t *count)
{
    store_place place;

    store_bytecode_place(&place);
    return store_load(board, &place, bytecode, capacity, count);
}

bool store_save_settings(hal_board *board, const uint16_t *settings, uint16_t count)
{
    store_place place;

    store_settings_place(&place);
    return store_save(board, &place, settings, count);
}

bool store_load_settings(hal_board *board, uint16_t *settings, uint16_t capacity, uint16_t *count)
{
    store_place place;

    store_settings_place(&place);
    return store_load(board, &place, settings, capacity, count);
}

uint16_t store_node_id(hal_board *board, uint16_t without_settings)
{
    uint16_t settings[STORE_SETTINGS_WORDS];
    uint16_t count;

    if (store_load_settings(board, settings, STORE_SETTINGS_WORDS, &count) &&
        count > STORE_SETTINGS_NODE_ID && settings[STORE_SETTINGS_NODE_ID] >= 1u &&
        settings[STORE_SETTINGS_NODE_ID] <= STORE_SETTINGS_NODE_ID_MAX)
        return settings[STORE_SETTINGS_NODE_ID];
    return without_settings;
}
