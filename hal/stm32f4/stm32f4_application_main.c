// The STM32F4 application image's entry point: the single static board,
// robot board layer and firmware, the main loop, and the vectors that
// forward to the board's handlers (stm32f4_startup.c's table calls them).
// The only mutable file-scope state of the image.

#include "bootloader/bytecode_store.h"
#include "firmware/epuck_firmware.h"
#include "stm32f4_board.h"

#include STM32F4_ROBOT_HEADER

// Without a selector the node id is the stored settings', else 1.
#define NO_SELECTOR 0u

static hal_board board;
static epuck_robot robot;
static epuck_firmware firmware;
#ifdef STM32F4_RAM_FLASH_BASE
static stm32f4_ram_flash ram_flash __attribute__((section(".noinit")));
#endif

int main(void)
{
#ifdef STM32F4_RAM_FLASH_BASE
    board.ram_flash = &ram_flash;
#endif
    stm32f4_board_init(&board);
    epuck_firmware_init(&firmware, &board, &robot, epuck_store_node_id(&board, NO_SELECTOR));
    for (;;) {
        if (!epuck_firmware_poll(&firmware))
            hal_idle(&board);
    }
    return 0;
}

void stm32f4_systick_vector(void)
{
    stm32f4_on_systick(&board);
}

void stm32f4_usart1_vector(void)
{
    stm32f4_on_usart1(&board);
}
