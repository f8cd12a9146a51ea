/* Numbers written as text at the speed of the disk: printf's %.Ng of a float, exact and
 * without printf (docs/mesh.md#number-text). */
#ifndef SYL_UTIL_NUMTEXT_H
#define SYL_UTIL_NUMTEXT_H

/* The room a number's text may use at p (the text itself is at most 32 bytes) */
#define NUMTEXT_ROOM 48

/* Exactly what sprintf(p, "%.*g", prec, x) writes (glibc: the exact value rounded to prec
 * significant digits, ties to even; "-0", "nan", "inf" as printf spells them). Fast when x
 * is a float's value and 1 <= prec <= 9, the writers' case; otherwise printf itself.
 * Writes no terminating zero; returns the end. p needs NUMTEXT_ROOM bytes. */
char *numtext_g(char *p, double x, int prec);

/* v in decimal, as "%lld" writes it; returns the end (at most 20 bytes, no terminating zero). */
char *numtext_int(char *p, long long v);

#endif
