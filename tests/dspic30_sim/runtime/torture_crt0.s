; TEST-ONLY start-up code for the bare programs the simulator's tests run
; (the GCC torture corpus, the differential programs). It stands in for the
; project's hal/dspic30 start-up until that is on this branch, and is to be
; replaced by it. Written from the dsPIC30F manuals (stack pointer and
; SPLIM, CORCON.PSV and PSVPAG) and the toolchain's description of the
; linker's initialisation template (../shared/toolchains/pic30/README.md):
; with --no-pack-data, .dinit is a list of records, each of three program
; words (destination address, length in bytes, format), format 0 clearing
; the bytes and format 1 copying two bytes from each following program word
; (its low 16 bits); a destination of 0 ends the list.

        .equ    SPLIM, 0x0020
        .equ    TBLPAG, 0x0032
        .equ    PSVPAG, 0x0034
        .equ    CORCON, 0x0044
        .equ    CORCON_PSV, 2

        .section .init, code
        .global __reset
__reset:
        mov     #__SP_init, w15
        mov     #__SPLIM_init, w0
        mov     w0, SPLIM
        nop                             ; SPLIM is not used by the next instruction
        mov     #__const_psvpage, w0
        mov     w0, PSVPAG
        bset    CORCON, #CORCON_PSV

        ; The data template: W1 walks it (TBLPAG:W1), W2 is the destination.
        ; A program without initialised data has no template (both
        ; symbols 0, where the reset GOTO lies).
        mov     #__dinit_tblpage, w0
        mov     w0, TBLPAG
        mov     #__dinit_tbloffset, w1
        ior     w0, w1, w2
        bra     z, data_done
next_record:
        tblrdl  [w1++], w2              ; destination (the next program word: PC + 2)
        cp0     w2
        bra     z, data_done
        tblrdl  [w1++], w3              ; length in bytes
        tblrdl  [w1++], w4              ; format
        cp0     w4
        bra     nz, copy
clear:
        cp0     w3
        bra     z, next_record
        clr.b   [w2++]
        dec     w3, w3
        bra     clear
copy:
        cp0     w3
        bra     z, next_record
        tblrdl  [w1++], w5              ; two bytes per program word
        mov.b   w5, [w2++]
        dec     w3, w3
        bra     z, next_record
        swap    w5
        mov.b   w5, [w2++]
        dec     w3, w3
        bra     copy
data_done:
        call    _main
        reset

; Every vector without a handler leads here: an unexpected trap or
; interrupt restarts the chip (the simulator reports the trap).
        .global __DefaultInterrupt
__DefaultInterrupt:
        reset

        .end
