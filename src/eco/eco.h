/* Inside the ecosystem simulation (sylva/ecosystem.h). */
#ifndef SYL_ECO_H
#define SYL_ECO_H
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "sylva/ecosystem.h"

/* The in-process exchange (exchange.c). */
typedef struct EcoLocal EcoLocal;
EcoLocal *eco_local_new(int ntiles, SylEcoExchange *ops);
void eco_local_free(EcoLocal *l);

/* For the library's work split over ranks outside the simulation (forest/snapshot.c: a
 * snapshot's picture, split by rows): sum adds v over the ranks, in place (one process:
 * unchanged); gather puts every rank's bytes, in rank order, into *all (malloc'ed) on rank 0,
 * with each rank's length in lens[rank] (lens: size entries, rank 0's); *all = NULL
 * elsewhere. SYL_OK or SYL_ELIMIT. (mpi.c, mpi_none.c) */
void eco_mpi_sum(SylEcoMpi *mpi, int64_t *v, size_t n);
int eco_mpi_gather(SylEcoMpi *mpi, const void *mine, size_t n, uint8_t **all, size_t *lens);

/* Tiles to ranks (balance.c): contiguous runs of about equal plants (NULL: tiles alike). */
void eco_balance_cut(const int64_t *plants, int ntiles, int nranks, int *owner);

/* The purposes random streams are keyed by, with (plant id, year); ECO_RNG_FACTOR + f: the
 * death by factor f's unsuitability (mortality zamuda: his generator per factor). */
enum { ECO_RNG_SHADE = 1, ECO_RNG_STRESS, ECO_RNG_SEEDS, ECO_RNG_ARRIVE, ECO_RNG_GERMINATE, ECO_RNG_LIFE, ECO_RNG_FACTOR };

/* How well x of factor f suits species s, 0..1, by its tolerance curve (vigour.c). */
double eco_suitability(const SylEcoSpecies *s, int f, double x);

#endif
