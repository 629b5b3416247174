# The portable VM core: interpreter, verifier and debug commands. Built for
# the host here, with the host target's switches (computed-goto dispatch,
# the faster one with gcc and clang: docs/benchmarks.md); the firmware
# targets compile the same files with their own compilers and configuration.
LIBRARIES += aseba_vm
aseba_vm_SOURCES := vm/vm.c vm/vm_debug.c vm/vm_verify.c vm/vm_native_text.c

# The node: protocol 5 on any byte stream, around the VM (protocol.md).
LIBRARIES += aseba_node
aseba_node_SOURCES := vm/node.c vm/node_send.c vm/node_description.c vm/node_crc.c
