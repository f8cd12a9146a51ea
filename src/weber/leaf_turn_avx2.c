/* The leaves' turns (leaf_turn.h) compiled for AVX2: eight lanes in one register where the
 * x86-64 baseline needs two. GCC on x86-64 only (its target pragma); elsewhere never chosen. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#pragma GCC target("avx2")
#define WEBER_AVX2 1
#endif
#include "weber/leaf_turn.h"

#ifdef WEBER_AVX2
void weber_leaf_turn_avx2(Leaves8 *q, bool turned, float bend) { v8_leaf_turn(q, turned, bend); }
bool weber_leaf_avx2(void) { return __builtin_cpu_supports("avx2"); }
#else
void weber_leaf_turn_avx2(Leaves8 *q, bool turned, float bend) { v4_leaf_turn(q, turned, bend); }
bool weber_leaf_avx2(void) { return false; }
#endif
