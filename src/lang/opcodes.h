/* The expression VM's instruction set, listed once. An instruction is a 32-bit word:
 * the opcode in the low 8 bits and one operand in the high 24 bits. */
#ifndef SYL_OPCODES_H
#define SYL_OPCODES_H
#include <stdint.h>

/* X(name, operand kind, stack effect). Operand kinds: N none, K constant index,
 * L local slot, J jump target, B builtin id, F function index, C curve index. */
#define SYL_OPCODES(X)                                                   \
    X(PUSHK, K, +1) /* push constant */                                  \
    X(LOCAL, L, +1) /* push local (a bound parameter) */                 \
    X(ADD, N, -1) X(SUB, N, -1) X(MUL, N, -1) X(DIV, N, -1)              \
    X(MOD, N, -1) X(POW, N, -1)                                          \
    X(ADDK, K, 0) X(SUBK, K, 0) X(MULK, K, 0) X(DIVK, K, 0) /* top op k */ \
    X(NEG, N, 0) X(NOT, N, 0)                                            \
    X(LT, N, -1) X(LE, N, -1) X(GT, N, -1) X(GE, N, -1)                  \
    X(EQ, N, -1) X(NE, N, -1)                                            \
    X(JMP, J, 0)     /* pc = a */                                        \
    X(JFALSE, J, -1) /* pop; jump if zero */                             \
    X(ANDJ, J, 0)    /* top zero: jump (keep 0); else pop */             \
    X(ORJ, J, 0)     /* top nonzero: jump (keep 1); else pop */          \
    X(BOOL, N, 0)    /* top = top != 0 */                                \
    X(CALLB, B, 0)   /* builtin: pops its arguments, pushes result */    \
    X(CALLF, F, 0)   /* user function */                                 \
    X(CURVE, C, 0)   /* piecewise-linear curve of top */                 \
    X(RET, N, 0)

typedef enum {
#define SYL_OP_ENUM(name, kind, effect) OP_##name,
    SYL_OPCODES(SYL_OP_ENUM)
#undef SYL_OP_ENUM
    OP__COUNT
} Opcode;

#define INSTR(op, a) ((uint32_t)(op) | ((uint32_t)(a) << 8))
#define INSTR_OP(i) ((Opcode)((i)&0xffu))
#define INSTR_A(i) ((i) >> 8)
#define OPERAND_MAX 0xffffffu

extern const char *const syl_op_names[OP__COUNT];
extern const char syl_op_kinds[OP__COUNT];
extern const signed char syl_op_effects[OP__COUNT]; /* stack change; calls: see compiler */

#endif
