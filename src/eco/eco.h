/* Inside the ecosystem simulation (sylva/ecosystem.h). */
#ifndef SYL_ECO_H
#define SYL_ECO_H
#include <stdbool.h>
#include <stddef.h>

#include "sylva/ecosystem.h"

/* The in-process exchange (exchange.c). */
typedef struct EcoLocal EcoLocal;
EcoLocal *eco_local_new(int ntiles, SylEcoExchange *ops);
void eco_local_free(EcoLocal *l);

/* The purposes random streams are keyed by, with (plant id, year). */
enum { ECO_RNG_SHADE = 1, ECO_RNG_STRESS, ECO_RNG_SEEDS, ECO_RNG_ARRIVE, ECO_RNG_GERMINATE, ECO_RNG_LIFE };

#endif
