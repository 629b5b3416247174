// The STM32F405/407's registers the port uses, by address, and the one
// door to them. Addresses and bits are those of ST's reference manual RM0090
// (the STM32F405/415, 407/417, 427/437 and 429/439) and of ARM's Cortex-M4
// (the System Control Space); QEMU's netduinoplus2 models the same map for
// what it models (USART1, SysTick, the NVIC, the SCB).

#ifndef STM32F4_REGISTERS_H
#define STM32F4_REGISTERS_H

#include <stdint.h>

// --- reset and clock control (RM0090 §7.3) ------------------------------------
#define STM32F4_RCC_CR             0x40023800ul
#define STM32F4_RCC_PLLCFGR        0x40023804ul
#define STM32F4_RCC_CFGR           0x40023808ul
#define STM32F4_RCC_AHB1ENR        0x40023830ul
#define STM32F4_RCC_APB2ENR        0x40023844ul
#define STM32F4_RCC_CR_HSEON       (1ul << 16)
#define STM32F4_RCC_CR_HSERDY      (1ul << 17)
#define STM32F4_RCC_CR_PLLON       (1ul << 24)
#define STM32F4_RCC_CR_PLLRDY      (1ul << 25)
#define STM32F4_PLLCFGR_PLLSRC_HSE (1ul << 22)
#define STM32F4_PLLCFGR_N_SHIFT    6u
#define STM32F4_PLLCFGR_P_SHIFT    16u // (P / 2) - 1
#define STM32F4_PLLCFGR_Q_SHIFT    24u
#define STM32F4_CFGR_SW_PLL        0x2ul
#define STM32F4_CFGR_SWS_MASK      0xCul
#define STM32F4_CFGR_SWS_PLL       0x8ul
#define STM32F4_CFGR_PPRE1_DIV4    (0x5ul << 10) // APB1 = AHB / 4
#define STM32F4_CFGR_PPRE2_DIV2    (0x4ul << 13) // APB2 = AHB / 2
#define STM32F4_AHB1ENR_GPIOAEN    (1ul << 0)
#define STM32F4_APB2ENR_USART1EN   (1ul << 4)

// --- flash interface (RM0090 §3.8) --------------------------------------------------
#define STM32F4_FLASH_ACR          0x40023C00ul
#define STM32F4_FLASH_KEYR         0x40023C04ul
#define STM32F4_FLASH_SR           0x40023C0Cul
#define STM32F4_FLASH_CR           0x40023C10ul
#define STM32F4_FLASH_KEY1         0x45670123ul
#define STM32F4_FLASH_KEY2         0xCDEF89ABul
#define STM32F4_ACR_PRFTEN         (1ul << 8)
#define STM32F4_ACR_ICEN           (1ul << 9)
#define STM32F4_ACR_DCEN           (1ul << 10)
#define STM32F4_FLASH_SR_EOP       (1ul << 0)
#define STM32F4_FLASH_SR_ERRORS    0xF2ul // OPERR, WRPERR, PGAERR, PGPERR, PGSERR
#define STM32F4_FLASH_SR_BSY       (1ul << 16)
#define STM32F4_FLASH_CR_PG        (1ul << 0)
#define STM32F4_FLASH_CR_SER       (1ul << 1)
#define STM32F4_FLASH_CR_SNB_SHIFT 3u
#define STM32F4_FLASH_CR_PSIZE_32  (2ul << 8) // 32-bit parallelism: 2.7 to 3.6 V
#define STM32F4_FLASH_CR_STRT      (1ul << 16)
#define STM32F4_FLASH_CR_LOCK      (1ul << 31)

// --- GPIO port A (RM0090 §8.4): USART1 on PA9 (TX) and PA10 (RX) -------------------
#define STM32F4_GPIOA_MODER     0x40020000ul
#define STM32F4_GPIOA_AFRH      0x40020024ul
#define STM32F4_MODER_ALTERNATE 0x2ul
#define STM32F4_AF_USART1       7ul

// --- USART1 (RM0090 §30.6) ----------------------------------------------------------
#define STM32F4_USART1_SR        0x40011000ul
#define STM32F4_USART1_DR        0x40011004ul
#define STM32F4_USART1_BRR       0x40011008ul
#define STM32F4_USART1_CR1       0x4001100Cul
#define STM32F4_USART_SR_ORE     (1ul << 3)
#define STM32F4_USART_SR_RXNE    (1ul << 5)
#define STM32F4_USART_SR_TXE     (1ul << 7)
#define STM32F4_USART_CR1_RE     (1ul << 2)
#define STM32F4_USART_CR1_TE     (1ul << 3)
#define STM32F4_USART_CR1_RXNEIE (1ul << 5)
#define STM32F4_USART_CR1_TXEIE  (1ul << 7)
#define STM32F4_USART_CR1_UE     (1ul << 13)
#define STM32F4_IRQ_USART1       37u // position in the vector table after the 16 system entries

// --- Cortex-M4 system control space (ARMv7-M architecture reference) --------------
#define STM32F4_SYST_CSR           0xE000E010ul
#define STM32F4_SYST_RVR           0xE000E014ul
#define STM32F4_SYST_CVR           0xE000E018ul
#define STM32F4_SYST_CSR_ENABLE    (1ul << 0)
#define STM32F4_SYST_CSR_TICKINT   (1ul << 1)
#define STM32F4_SYST_CSR_CLKSOURCE (1ul << 2)   // the processor clock
#define STM32F4_NVIC_ISER0         0xE000E100ul // + 4 per 32 interrupts
#define STM32F4_NVIC_IPR0          0xE000E400ul // one byte per interrupt
#define STM32F4_SCB_AIRCR          0xE000ED0Cul
#define STM32F4_SCB_SHPR3          0xE000ED20ul                // bits 31:24: SysTick's priority
#define STM32F4_AIRCR_RESET        (0x05FAul << 16 | 1ul << 2) // VECTKEY, SYSRESETREQ
// Priorities live in the top 4 bits of each byte on the STM32F4.
#define STM32F4_PRIORITY_SHIFT 4u

static inline uint32_t stm32f4_read(uint32_t address)
{
    return *(volatile uint32_t *)address;
}

static inline void stm32f4_write(uint32_t address, uint32_t value)
{
    *(volatile uint32_t *)address = value;
}

static inline void stm32f4_set_bits(uint32_t address, uint32_t mask)
{
    stm32f4_write(address, stm32f4_read(address) | mask);
}

static inline void stm32f4_clear_bits(uint32_t address, uint32_t mask)
{
    stm32f4_write(address, stm32f4_read(address) & ~mask);
}

static inline void stm32f4_write_byte(uint32_t address, uint8_t value)
{
    *(volatile uint8_t *)address = value;
}

// PRIMASK: masks every configurable interrupt; returns whether it was set.
static inline uint32_t stm32f4_interrupts_off(void)
{
    uint32_t primask;
    __asm__ volatile("mrs %0, primask\n cpsid i" : "=r"(primask)::"memory");
    return primask;
}

static inline void stm32f4_interrupts_restore(uint32_t primask)
{
    __asm__ volatile("msr primask, %0" ::"r"(primask) : "memory");
}

static inline void stm32f4_wait_for_interrupt(void)
{
    __asm__ volatile("wfi" ::: "memory");
}

static inline void stm32f4_data_barrier(void)
{
    __asm__ volatile("dsb" ::: "memory");
}

#endif
