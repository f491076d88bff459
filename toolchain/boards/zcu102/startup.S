/* Start-up of the ZynqMP (QEMU xlnx-zcu102) images: AArch64 EL3 → AArch32 Secure SVC.

   QEMU's loader (-device loader,file=IMAGE.elf,cpu-num=0) starts APU core 0 (Cortex-A53) at
   the ELF entry in AArch64 EL3 with `-M xlnx-zcu102,secure=on`. curio_boot64 holds six A64
   instructions, as words (arm-none-eabi-as assembles A32/T32 only):
     msr scr_el3, xzr      SCR_EL3 = 0: EL1 and below are AArch32 (RW=0), Secure (NS=0),
                           IRQ/FIQ taken at EL1 (IRQ=FIQ=0)
     mov x0, #0x1d3        SPSR: AArch32 (M[4]=1) SVC mode, A, I and F masked
     msr spsr_el3, x0
     adr x0, #12           → curio_reset_a32, right after the eret
     msr elr_el3, x0
     eret
   From there on everything is AArch32, the state a Cortex-R5F (ARMv7-R) also runs in: the
   same A32/T32 code, DSP instructions (SXTB16, SMLAD), VFP, GICv2 and exception model; only
   the boot stub and the MMU/MPU differ (docs/deploy.md).

   curio_reset_a32: stacks for IRQ, abort and undefined modes and the SVC (main) stack, VBAR
   at curio_vectors_a32 (SCTLR.V=0), the FPU on (CPACR cp10/cp11, FPEXC.EN), then
   curio_reset_c (startup.c).
   curio_irq_entry: saves the caller-saved integer and VFP registers and FPSCR on the SVC
   stack (8-byte aligned), calls curio_irq_dispatch (C++: hal/zynqmp/gic.cpp), returns with
   RFE. IRQs do not nest (CPSR.I stays set in the handler). */
        .syntax unified

        .section .boot64, "ax"
        .global curio_boot64
        .type curio_boot64, %function
curio_boot64:
        .word 0xd51e111f  /* msr  scr_el3, xzr */
        .word 0xd2803a60  /* mov  x0, #0x1d3 */
        .word 0xd51e4000  /* msr  spsr_el3, x0 */
        .word 0x10000060  /* adr  x0, #12 */
        .word 0xd51e4020  /* msr  elr_el3, x0 */
        .word 0xd69f03e0  /* eret */
        .arm
curio_reset_a32:
        cps     #0x12                 /* IRQ: only the SRS frame lands here... */
        ldr     sp, =__irq_stack_top
        cps     #0x17                 /* abort */
        ldr     sp, =__irq_stack_top
        cps     #0x1b                 /* undefined */
        ldr     sp, =__irq_stack_top
        cps     #0x13                 /* SVC: the main stack */
        ldr     sp, =__stack_top
        ldr     r0, =curio_vectors_a32
        mcr     p15, 0, r0, c12, c0, 0   /* VBAR */
        mrc     p15, 0, r0, c1, c0, 0    /* SCTLR */
        bic     r0, r0, #(1 << 13)       /* V=0: vectors at VBAR */
        bic     r0, r0, #(1 << 30)       /* TE=0: exceptions in ARM state */
        mcr     p15, 0, r0, c1, c0, 0
        mrc     p15, 0, r0, c1, c0, 2    /* CPACR */
        orr     r0, r0, #(0xF << 20)     /* cp10, cp11: full access */
        mcr     p15, 0, r0, c1, c0, 2
        isb
        mov     r0, #0x40000000          /* FPEXC.EN */
        vmsr    fpexc, r0
        b       curio_reset_c

        .section .vectors, "ax"
        .align  5
        .global curio_vectors_a32
curio_vectors_a32:
        b       curio_reset_a32
        b       curio_undef_entry
        b       curio_svc_entry
        b       curio_pabt_entry
        b       curio_dabt_entry
        nop
        b       curio_irq_entry
        b       curio_fiq_entry

curio_undef_entry:
        mov     r0, #1
        b       curio_fault_entry
curio_svc_entry:
        mov     r0, #2
        b       curio_fault_entry
curio_pabt_entry:
        mov     r0, #3
        b       curio_fault_entry
curio_dabt_entry:
        mov     r0, #4
        b       curio_fault_entry
curio_fiq_entry:
        mov     r0, #7
curio_fault_entry:
        mov     r1, lr
        ldr     sp, =__irq_stack_top
        bl      curio_fault              /* prints the kind and address, exits */
1:      b       1b

curio_irq_entry:
        sub     lr, lr, #4
        srsdb   sp!, #0x13               /* LR_irq, SPSR_irq onto the SVC stack */
        cps     #0x13
        push    {r0-r3, r12, lr}
        and     r1, sp, #4               /* 8-byte alignment for the C++ call */
        sub     sp, sp, r1
        vmrs    r2, fpscr
        push    {r1, r2}
        vpush   {d0-d7}
        vpush   {d16-d31}
        bl      curio_irq_dispatch
        vpop    {d16-d31}
        vpop    {d0-d7}
        pop     {r1, r2}
        vmsr    fpscr, r2
        add     sp, sp, r1
        pop     {r0-r3, r12, lr}
        rfeia   sp!
