/* The host side of the differential programs: reports on standard output. */

#include "harness.h"

#include <stdio.h>

void report(const char *name, uint32_t value)
{
    printf("%s %08lx\n", name, (unsigned long)value);
}

int main(void)
{
    differential_main();
    printf("EXIT 0\n");
    return 0;
}
