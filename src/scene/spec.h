/* A scene block's directives read into plants, obstacles, the ground and the sun (spec.c). */
#ifndef SYL_SCENE_SPEC_H
#define SYL_SCENE_SPEC_H
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "sylva/sylva.h"

/* One plant of a scene. */
typedef struct ScenePlant {
    const char *model;   /* a model of this file, or NULL when file is set */
    const char *file;    /* "path.syl" or "path.syl:Model", relative to the scene's file */
    float at[3];
    bool seed_set, years_set;
    uint64_t seed;
    int years;
    int line, col;
} ScenePlant;

typedef struct SceneObstacle {
    const char *file;
    float at[3];
    float scale;
    bool terrain;        /* from `ground "file.obj"` */
    int line, col;
} SceneObstacle;

typedef struct SceneSpec {
    ScenePlant *plants;
    int nplants, plants_cap;
    SceneObstacle *obstacles;
    int nobstacles, obstacles_cap;
    float ground;
    bool ground_set;
    float sun[3];
    bool sun_set;
    int set_errors; /* of those read, the errors of --set scene.NAME */
} SceneSpec;

/* Read p's scene block (free with scene_spec_free). Returns the number of errors. Names of
 * plants are checked against the models of the file. */
int scene_spec_read(const SylProgram *p, SceneSpec *s, FILE *diag);
void scene_spec_free(SceneSpec *s);
/* A file the scene names (obstacle, ground, plant), relative to the scene's own file, into
 * *out (malloc'd), as syl_program_file decides (SYL_EIO: outside the folders the model may
 * read; SYL_ELIMIT: out of memory). With model not NULL (a plant), "file.syl:Model" is split:
 * *model is the model's name (malloc'd) or NULL. */
int scene_spec_path(const SylProgram *p, const char *file, char **model, char **out);

/* Compile the model of a plant file a scene names ("file.syl[:Model]"), as syl_program_file
 * and syl_text_is_model allow, checked as `sylva check` would; NULL with *status on failure
 * (reported on diag at the plant's line and column). */
SylProgram *scene_plant_file(const SylProgram *p, const char *file, int line, int col, FILE *diag, int *status);

/* Check p's scene block, as syl_validate does with a file's first model. Returns the
 * number of errors reported, negated when all are of --set. */
int scene_spec_check(const SylProgram *p, FILE *diag, bool files); /* files: warn about unreadable ones */

#endif
