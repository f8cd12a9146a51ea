/* Test-only fault switches (cli/testfaults.h): empty functions unless SYL_TEST_FAULTS. */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "cli/testfaults.h"

#ifdef SYL_TEST_FAULTS
static bool at(const char *rank_var, const char *year_var, int rank, int year) {
    const char *r = getenv(rank_var), *y = getenv(year_var);
    return r && y && atoi(r) == rank && atoi(y) == year;
}

void cli_test_fault_year(int rank, int year) {
    /* a killed rank, for tests/run-mpi: the job must end with nothing half-written */
    if (at("SYLVA_TEST_FAIL_RANK", "SYLVA_TEST_FAIL_YEAR", rank, year)) {
        fprintf(stderr, "sylva: test: rank %d kills itself at year %d (SYLVA_TEST_FAIL_YEAR)\n", rank, year);
        fflush(stderr);
        raise(SIGKILL);
    }
    if (at("SYLVA_TEST_STOP_RANK", "SYLVA_TEST_STOP_YEAR", rank, year)) { /* the others must not wait for ever */
        fprintf(stderr, "sylva: test: rank %d stops itself at year %d (SYLVA_TEST_STOP_YEAR)\n", rank, year);
        fflush(stderr);
        raise(SIGSTOP);
    }
}

void cli_test_fault_gather(bool mpi, int rank) {
    /* a killed rank, for tests/run-mpi: the job must end with nothing written */
    const char *fr = getenv("SYLVA_TEST_FAIL_RANK");
    if (mpi && fr && atoi(fr) == rank && !getenv("SYLVA_TEST_FAIL_YEAR")) {
        fprintf(stderr, "sylva: test: rank %d kills itself before the gather (SYLVA_TEST_FAIL_RANK)\n", rank);
        fflush(stderr);
        raise(SIGKILL);
    }
}

unsigned long long cli_test_split_ns(void) {
    const char *v = getenv("SYLVA_TEST_SPLIT_NS");
    return v ? strtoull(v, NULL, 10) : 0;
}

void cli_test_pause_spawn(void) {
    if (getenv("SYLVA_TEST_PAUSE_SPAWN")) nanosleep(&(struct timespec){0, 200000000}, NULL);
}
#else
unsigned long long cli_test_split_ns(void) { return 0; }
void cli_test_pause_spawn(void) {}
void cli_test_fault_year(int rank, int year) { (void)rank, (void)year; }
void cli_test_fault_gather(bool mpi, int rank) { (void)mpi, (void)rank; }
#endif
