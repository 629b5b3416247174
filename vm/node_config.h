// Tunables of the node layer, with their defaults. A target overrides them
// in its one configuration header, named by TARGET_CONFIG (vm_config.h).

#ifndef NODE_CONFIG_H
#define NODE_CONFIG_H

#include "vm_config.h"

// A partial frame whose next byte is later than this is discarded (and
// counted): the sender gave up or bytes were lost. GCtronic's e-puck firmware
// uses the same value.
#ifndef NODE_INTER_BYTE_TIMEOUT_MS
#define NODE_INTER_BYTE_TIMEOUT_MS 500
#endif

// Instructions the VM may run per node_poll before the node looks at the
// network again (upstream microcontroller glue uses 1000).
#ifndef NODE_STEP_BUDGET
#define NODE_STEP_BUDGET 1000
#endif

// Outgoing frames are streamed to the transport in pieces of at most this
// many bytes, so the node needs no buffer of a whole frame for sending.
#ifndef NODE_TRANSMIT_CHUNK
#define NODE_TRANSMIT_CHUNK 32
#endif

#endif
