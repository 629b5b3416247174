# The portable VM core: interpreter and debug commands. Built for the host
# here; the firmware targets compile the same files with their own compilers.
LIBRARIES += aseba_vm
aseba_vm_SOURCES := vm/vm.c vm/vm_debug.c

# The node: protocol 5 on any byte stream, around the VM (protocol.md).
LIBRARIES += aseba_node
aseba_node_SOURCES := vm/node.c vm/node_send.c vm/node_description.c
