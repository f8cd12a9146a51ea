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

/* Tiles to ranks (balance.c): contiguous runs of about equal plants (NULL: tiles alike). */
void eco_balance_cut(const int64_t *plants, int ntiles, int nranks, int *owner);

/* The purposes random streams are keyed by, with (plant id, year); ECO_RNG_FACTOR + f: the
 * death by factor f's unsuitability (mortality zamuda: his generator per factor). */
enum { ECO_RNG_SHADE = 1, ECO_RNG_STRESS, ECO_RNG_SEEDS, ECO_RNG_ARRIVE, ECO_RNG_GERMINATE, ECO_RNG_LIFE, ECO_RNG_FACTOR };

/* How well x of factor f suits species s, 0..1, by its tolerance curve (vigour.c). */
double eco_suitability(const SylEcoSpecies *s, int f, double x);

#endif
