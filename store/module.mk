# The fail-safe bytecode store (the program a host saved, the node's
# settings), portable C99 on hal.h; the application and the bootloader use it.
LIBRARIES += aseba_store
aseba_store_SOURCES := store/bytecode_store.c
