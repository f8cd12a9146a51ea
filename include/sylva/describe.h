/* PROVISIONAL (branch `view`, issue 30): a stand-in with the agreed signature and JSON shape
 * until the directive-schema work (the `schema` branch) brings the real one, which replaces
 * this header and src/lang/describe.c at merge.
 *
 * The parameters of every model of p's file as JSON, for front ends that show them as
 * sliders (`sylva view`):
 *   {"file":"PATH","models":[{"name":"Plant","kind":"lsystem","line":1,"params":[
 *     {"name":"angle","type":"number","min":0,"max":360,"default":90,"value":25.7,
 *      "unit":"deg","doc":"turn angle of + and -","values":null,"aliases":[]}]}]}
 * type: number, integer, boolean, enum, list, curve, file, string; min/max null when
 * unbounded; values: an enum's words, or null. SYL_OK, or SYL_EIO when out failed. */
#ifndef SYLVA_DESCRIBE_H
#define SYLVA_DESCRIBE_H
#include <stdio.h>

#include "sylva.h"

#ifdef __cplusplus
extern "C" {
#endif

int syl_describe_json(const SylProgram *p, FILE *out);

#ifdef __cplusplus
}
#endif
#endif
