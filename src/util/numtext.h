/* Numbers written as text at the speed of the disk: the writers' two formats, exact and
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

/* The OBJ writer's short form: x with sig (1..9) significant digits and no exponent
 * ("0.25", "-3", "1234567"), the last digit rounded half away from zero; "%.*g" past
 * [1e-4, 1e9); 0 for -0 and non-finite values. Returns the end. p needs NUMTEXT_ROOM bytes:
 * the digits go out in fixed-size copies, and the bytes after the end are scratch. */
char *numtext_short(char *p, float x, int sig);

#endif
