; The C start-up of every dsPIC30F image of the project (application,
; bootloader, bare test programs), written from the dsPIC30F Family
; Reference Manual (stack pointer and SPLIM, CORCON.PSV and PSVPAG) and the
; 16-bit Language Tools Libraries' description of the linker's data
; initialisation template (.dinit). It replaces Microchip's crt0 from
; libpic30, which the GPL toolchain lacks; XC16 users link it the same way
; (-nostartfiles), so there is one start-up path to test, not two.
;
; The reset vector (or an image's GOTO table slot 0, or the bootloader's
; jump) leads to __reset. The symbols used here are made by the linker:
; __SP_init and __SPLIM_init (the stack it sized from the RAM left over),
; __const_psvpage (the program-memory page of the constants, the .const
; section), __dinit_tblpage and __dinit_tbloffset (where .dinit lies).

        .section .init, code
        .global __reset
__reset:
        ; The stack first: W15 above the data, SPLIM below the last word
        ; (a stack error trap fires when W15 passes it).
        mov     #__SP_init, w15
        mov     #__SPLIM_init, w0
        mov     w0, _SPLIM
        ; SPLIM must not be used by the next instruction (Family Reference
        ; Manual, stack pointer overflow): a NOP between.
        nop
        ; Constants in program memory are read through the PSV window at
        ; 0x8000 of data space: their page, and PSV on (CORCON bit 2).
        mov     #__const_psvpage, w0
        mov     w0, _PSVPAG
        bset    _CORCON, #2
        ; Initialised data and cleared .bss from the template, in C
        ; (dspic30_startup.c); the template's address is 24 bits: W1:W0.
        mov     #__dinit_tbloffset, w0
        mov     #__dinit_tblpage, w1
        call    _dspic30_initialise_data
        call    _main
        ; main never returns; if it does, start again as after a reset.
        reset

; Where the linker scripts send every interrupt and trap the image has no
; handler for: an unexpected one (a stack or address error, a spurious
; interrupt) restarts the chip, as Microchip's default handler does, rather
; than running on from an unknown state. In .init so that --gc-sections
; keeps it (only the scripts' vector expressions name it).
        .global __DefaultInterrupt
__DefaultInterrupt:
        reset

        .end
