/* The dsPIC side of the differential programs: reports on UART1 (polled),
   then "EXIT 0" as the torture tests end. */

#include "harness.h"

#define U1MODE  (*(volatile uint16_t *)0x020C)
#define U1STA   (*(volatile uint16_t *)0x020E)
#define U1TXREG (*(volatile uint16_t *)0x0210)
#define U1BRG   (*(volatile uint16_t *)0x0214)
#define UTXBF   (1u << 9)

static void put(char c)
{
    while (U1STA & UTXBF)
        ;
    U1TXREG = (uint8_t)c;
}

static void put_string(const char *s)
{
    while (*s)
        put(*s++);
}

void report(const char *name, uint32_t value)
{
    static const char digits[] = "0123456789abcdef";
    int shift;
    put_string(name);
    put(' ');
    for (shift = 28; shift >= 0; shift -= 4)
        put(digits[(value >> shift) & 0xF]);
    put('\n');
}

int main(void)
{
    U1BRG = 7;
    U1MODE = 0x8000;
    U1STA = 1u << 10;
    differential_main();
    put_string("EXIT 0\n");
    for (;;)
        ;
}
