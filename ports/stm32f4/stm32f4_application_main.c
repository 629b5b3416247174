// The STM32F4 application image's entry point: the single static board,
// robot devices and firmware, the main loop, and the vectors that forward
// to the board's handlers (stm32f4_startup.c's table calls them). The only
// mutable file-scope state of the image.

#include "firmware/firmware.h"
#include "store/bytecode_store.h"
#include "stm32f4_chip.h"

// The robot's devices the board has (its configuration names them).
#include STM32F4_DEVICES_HEADER

// Without a selector the node id is the stored settings', else 1.
#define NODE_ID_WITHOUT_SETTINGS 1u

static hal_board board;
static robot_devices robot;
static firmware_state firmware;
#ifdef STM32F4_RAM_FLASH_BASE
static stm32f4_ram_flash ram_flash __attribute__((section(".noinit")));
#endif

int main(void)
{
#ifdef STM32F4_RAM_FLASH_BASE
    board.ram_flash = &ram_flash;
#endif
    stm32f4_board_init(&board);
    firmware_init(&firmware, &board, &robot, store_node_id(&board, NODE_ID_WITHOUT_SETTINGS));
    for (;;) {
        if (!firmware_poll(&firmware))
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
