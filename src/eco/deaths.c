/* The causes of death a year's counts are kept by (sylva/ecosystem.h, SYL_ECO_DEATH_LIST). */
#include "sylva/ecosystem.h"

#define NAME(id, name) name,
static const char *const names[SYL_ECO_DEATH_CAUSES] = {SYL_ECO_DEATH_LIST(NAME)};
#undef NAME

const char *syl_ecosystem_death_name(SylEcoDeath cause) {
    return (unsigned)cause < SYL_ECO_DEATH_CAUSES ? names[cause] : "?";
}

int syl_ecosystem_death_of(SylTerrainFactor f) {
    switch (f) {
    case SYL_TERRAIN_ALTITUDE: return SYL_ECO_DEATH_ALTITUDE;
    case SYL_TERRAIN_SLOPE: return SYL_ECO_DEATH_SLOPE;
    case SYL_TERRAIN_ASPECT: return SYL_ECO_DEATH_ASPECT;
    case SYL_TERRAIN_WETNESS: case SYL_TERRAIN_HUMIDITY: return SYL_ECO_DEATH_HUMIDITY;
    case SYL_TERRAIN_INSOLATION: case SYL_TERRAIN_SUNNINESS: return SYL_ECO_DEATH_SUNNINESS;
    case SYL_TERRAIN_WIND: case SYL_TERRAIN_WINDINESS: return SYL_ECO_DEATH_WINDINESS;
    default: return -1;
    }
}
