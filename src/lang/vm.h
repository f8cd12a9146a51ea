/* The expression VM: runs one compiled expression over a frame of bound parameters. */
#ifndef SYL_VM_H
#define SYL_VM_H
#include <stdint.h>

#include "lang/program.h"
#include "util/rng.h"

typedef struct VmFault {
    int status;  /* EVAL_* */
    uint32_t pc; /* the instruction that failed */
} VmFault;

/* Evaluate the expression at pc. Returns EVAL_OK and *out, or an EVAL_* status with fault
 * set. A result that is not finite is an error. */
int vm_run(const SylProgram *p, uint32_t pc, const double *locals, Rng *rng, double *out, VmFault *fault);

#endif
