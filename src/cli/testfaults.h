/* Test-only fault switches: a rank that kills or stops itself, for tests/run-mpi and
 * checkpoint.test. They exist only in a build compiled with -DSYL_TEST_FAULTS (the Makefile's
 * tested tree, build/sylva); the installed binary (make install) has them compiled out. */
#ifndef SYL_CLI_TESTFAULTS_H
#define SYL_CLI_TESTFAULTS_H
#include <stdbool.h>

/* The end of year `year` on rank `rank`: SYLVA_TEST_FAIL_RANK/_YEAR kill it (SIGKILL),
 * SYLVA_TEST_STOP_RANK/_YEAR stop it (SIGSTOP). */
void cli_test_fault_year(int rank, int year);
/* Before a distributed picture's gather: SYLVA_TEST_FAIL_RANK without _YEAR kills the rank. */
void cli_test_fault_gather(bool mpi, int rank);
/* SylDeriveOptions.split_ns from SYLVA_TEST_SPLIT_NS (0 without it): tests/cases/threads.test
 * splits passes far cheaper than the default would, to check the chunks' bytes. */
unsigned long long cli_test_split_ns(void);
/* SYLVA_TEST_PAUSE_SPAWN: a fifth of a second after ffmpeg started, before its pid is noted,
 * when a signal must wait for the pid (tests/cases/trust.test sends one then). */
void cli_test_pause_spawn(void);

#endif
