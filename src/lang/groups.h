/* Groups (tables): which are used at a step, and the rule table of a set of them. */
#ifndef SYL_LANG_GROUPS_H
#define SYL_LANG_GROUPS_H
#include <stdbool.h>
#include <stdint.h>

#include "lang/program.h"
#include "lang/vm.h"

/* The rules of table `table` (TABLE_*) that take part while the groups of `active` are:
 * those of the active groups, then those outside any group, each part in file order. Built
 * into t (its arrays from a, whose oom may be NULL). Returns false when out of memory. */
bool lang_table_select(const SylProgram *p, int table, uint64_t active, RuleTable *t, Arena *a);

/* The set of groups used at `step` (bit i: group i). Returns EVAL_OK, or the EVAL_* status of
 * a condition that failed, with *fault and *group (its index) set. */
int lang_groups_active(const SylProgram *p, int step, uint64_t seed, uint64_t *active, VmFault *fault, int *group);

#endif
