/* What a model's parameters are: every model of a file with every parameter (its `param`s,
 * an L-system's settings, a block's directives from its kind's schema), with type, range,
 * default, unit, meaning and current value. The contract that sliders, keyword arguments and
 * panels read (docs/cli.md, `sylva describe`). */
#ifndef SYLVA_DESCRIBE_H
#define SYLVA_DESCRIBE_H
#include <stdio.h>

#include "sylva/sylva.h"

/* Write, as JSON, every model of p's file (p as syl_compile returns it for the file; the
 * other models are compiled beside it with the same --set values):
 *   {"file":"PATH","models":[{"name":"Plant","kind":"lsystem","line":1,"params":[
 *     {"name":"angle","type":"number","min":-1e9,"max":1e9,"default":45,"value":25.7,
 *      "unit":"deg","doc":"...","values":null,"aliases":[]}, ...]}]}
 * type: number, integer, boolean, enum, list, curve, file or string; min/max null when
 * unbounded; values: an enum's words, else null. Returns SYL_OK, or SYL_EIO when out could
 * not be written. */
int syl_describe_json(const SylProgram *p, FILE *out);
/* The same as a table for people: one line a parameter. */
int syl_describe_text(const SylProgram *p, FILE *out);

#endif
