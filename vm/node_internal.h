// What the node's files share among themselves: the frame writer, the
// outgoing messages and the callbacks the VM reports through.

#ifndef NODE_INTERNAL_H
#define NODE_INTERNAL_H

#include "node.h"

// Word positions in a frame: the header, then the payload.
#define FRAME_LENGTH  0
#define FRAME_SOURCE  1
#define FRAME_TYPE    2
#define FRAME_PAYLOAD 3

// The frame writer streams one frame through the transport: begin announces
// the payload length, put functions append, end completes it. The frame is
// well-formed whatever the callers do: bytes beyond the announced length are
// dropped and missing ones are sent as zeros.
void node_frame_begin(node_state *node, uint16_t type, uint16_t payload_length);
void node_frame_put_byte(node_state *node, uint8_t byte);
void node_frame_put_u16(node_state *node, uint16_t value);
void node_frame_put_string(node_state *node, const char *text, uint8_t length);
void node_frame_end(node_state *node);

// Bytes of `text` that fit a protocol string (255) without cutting a UTF-8
// character; 0 for NULL.
uint8_t node_string_length(const char *text);

// Sends a frame whose payload is `count` uint16 words.
void node_send_words(node_state *node, uint16_t type, const uint16_t *words, uint16_t count);

// Sends a frame whose payload is `word` then the string `text`, cut to 255
// bytes (named variables and node-specific errors).
void node_send_word_and_string(node_state *node, uint16_t type, uint16_t word, const char *text);

// VARIABLES answers for `length` words from `start`, clamped to the memory
// and split so that none exceeds NODE_MAX_VARIABLES_WORDS values.
void node_send_variables(node_state *node, uint16_t start, uint16_t length);

// Asks for the description (DESCRIPTION, then every named variable, local
// event and native function), for node_continue_description to send; after
// the one being sent, if any.
void node_start_description(node_state *node);

// Sends the description's next frame; false when none is left.
bool node_continue_description(node_state *node);

// The VM's reports, encoded as protocol messages; the context is the node.
extern const vm_callbacks node_vm_callbacks;

#endif
