// The node's switches, the target's (vm_config.h): this file stops a build
// whose configuration does not give them.
//
//   NODE_INTER_BYTE_TIMEOUT_MS  a partial frame whose next byte is later
//                               than this is discarded (and counted): the
//                               sender gave up or bytes were lost
//   NODE_STEP_BUDGET            instructions the VM may run per node_poll
//                               before the node looks at the network again
//   NODE_TRANSMIT_CHUNK         outgoing frames are streamed to the
//                               transport in pieces of at most this many
//                               bytes, so the node needs no buffer of a
//                               whole frame for sending
//   NODE_DESCRIPTION_FRAMES_PER_POLL
//                               frames of a description sent per node_poll
//                               that found no received frame: 1 where the
//                               link is slow beside the receive buffer (the
//                               e-puck's UART), the whole description (as
//                               one answer, as hosts expect) where sending
//                               never waits

#ifndef NODE_CONFIG_H
#define NODE_CONFIG_H

#include "vm_config.h"

#if !defined(NODE_INTER_BYTE_TIMEOUT_MS) || !defined(NODE_STEP_BUDGET) ||                          \
  !defined(NODE_TRANSMIT_CHUNK) || !defined(NODE_DESCRIPTION_FRAMES_PER_POLL)
#error                                                                                             \
  "the target's configuration must give NODE_INTER_BYTE_TIMEOUT_MS, NODE_STEP_BUDGET, NODE_TRANSMIT_CHUNK and NODE_DESCRIPTION_FRAMES_PER_POLL"
#endif

#endif
