// The VM benchmark's workload on an AVR (avr-gcc, 16-bit int: a proxy for
// the dsPIC), for bench/avr_step_counter.c to run under simavr. The
// workload's bytecode and memory sizes come from a header that
// scripts/bench.sh generates with `bench-vm bytecode` (VM_WORKLOAD_HEADER).
// Port B bit 0 is set while event `go` runs, so the counter measures that
// and nothing else; ports C and D then hold a checksum of the variables,
// which the counter prints so that the run can be checked against the host.

#include <avr/interrupt.h>
#include <avr/io.h>
#include <avr/sleep.h>
#include <stddef.h>

#include "vm/vm.h"

#include VM_WORKLOAD_HEADER

static uint16_t bytecode[VM_WORKLOAD_BYTECODE_WORDS];
static int16_t variables[VM_WORKLOAD_VARIABLE_WORDS];
static int16_t stack[VM_WORKLOAD_STACK_WORDS];
static vm_state vm;

static void ignore_emit(void *context, uint16_t event, const int16_t *payload, uint16_t count)
{
    (void)context;
    (void)event;
    (void)payload;
    (void)count;
}

static void ignore_report(void *context, uint16_t type, const uint16_t *words, uint16_t count)
{
    (void)context;
    (void)type;
    (void)words;
    (void)count;
}

static void ignore_error(void *context, uint16_t pc, const char *message)
{
    (void)context;
    (void)pc;
    (void)message;
}

static const vm_callbacks callbacks = { ignore_emit, ignore_report, ignore_error };
static const vm_native_table no_natives = { NULL, 0, NULL };

int main(void)
{
    vm_memory memory = { bytecode,  VM_WORKLOAD_BYTECODE_WORDS,
                         variables, VM_WORKLOAD_VARIABLE_WORDS,
                         stack,     VM_WORKLOAD_STACK_WORDS,
                         0 };
    uint16_t checksum = 0;
    uint16_t i;

    vm_init(&vm, &memory, 1, &no_natives, &callbacks, NULL);
    vm_set_bytecode(&vm, 0, vm_workload, sizeof(vm_workload) / sizeof(vm_workload[0]));
    vm_command_run(&vm);
    vm_run(&vm, 0); // init
    vm_setup_event(&vm, VM_WORKLOAD_EVENT);
    DDRB = 1;
    PORTB = 1;
    vm_run(&vm, 0);
    PORTB = 0;
    for (i = 0; i < VM_WORKLOAD_VARIABLE_WORDS; i++)
        checksum = (uint16_t)(checksum * 31u + (uint16_t)variables[i]);
    PORTC = (uint8_t)checksum;
    PORTD = (uint8_t)(checksum >> 8);
    // Sleeping with interrupts off ends the simulation.
    cli();
    sleep_enable();
    sleep_cpu();
    return 0;
}
