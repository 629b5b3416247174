# The portable VM core: interpreter and debug commands. Built for the host
# here; the firmware targets compile the same files with their own compilers.
LIBRARIES += aseba_vm
aseba_vm_SOURCES := vm/vm.c vm/vm_debug.c
