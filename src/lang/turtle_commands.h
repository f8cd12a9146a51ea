/* The turtle's commands, listed once (docs/turtle.md §3): name, default argument and flags.
 *
 * The compiler resolves every symbol into one of them when it makes the symbol
 * (Symbol.turtle), so the drawing turtle, the query pass and the shoot-plan reader look a
 * module's command up instead of comparing names. It lives in lang because the compiler
 * resolves it; it uses nothing but the C library. */
#ifndef SYL_LANG_TURTLE_COMMANDS_H
#define SYL_LANG_TURTLE_COMMANDS_H
#include <stddef.h>
#include <stdint.h>
#include <string.h>

/* What a command's first parameter is when it has none. */
typedef enum {
    TA_NONE,  /* none: it needs its parameters, or does something else without (`!`, `'`) */
    TA_STEP,  /* the model's step */
    TA_ANGLE, /* the model's angle */
    TA_WIDTH, /* the current width */
    TA_ZERO,
    TA_ONE,
} TurtleDefault;

/* What a command does, as its readers need to know it. */
enum {
    TF_DRAWS = 1 << 0,  /* adds to the skeleton: a segment, a polygon, an organ */
    TF_MOVES = 1 << 1,  /* changes the position */
    TF_TURNS = 1 << 2,  /* changes the frame */
    TF_STACK = 1 << 3,  /* `[`, `]`, `%` */
    TF_STEERS = 1 << 4, /* changes where later moves go: tropism, scale, polygons (F moves in one) */
    TF_STYLE = 1 << 5,  /* changes how later things are drawn: width, material, smoothness */
    TF_QUERY = 1 << 6,  /* a query module: the turtle (or the environment) writes its parameters */
    TF_ORGAN = 1 << 7,  /* an organ: a predefined surface or a sphere */
    TF_PLAN = 1 << 8,   /* read by the shoot-plan reader too (sot/shoot_rule.c) */
};

/* X(command, name, default, flags), one row per command, in the order of the enum (the
 * turtle relies on it: the six turns follow each other, the queries come last). The
 * command TC_SURFACE_UNKNOWN has no name of its own: it is any other name starting with `~`. */
#define TURTLE_COMMANDS(X)                                                         \
    X(TC_F, "F", TA_STEP, TF_DRAWS | TF_MOVES | TF_PLAN)                           \
    X(TC_G, "G", TA_STEP, TF_DRAWS | TF_MOVES)                                     \
    X(TC_f, "f", TA_STEP, TF_MOVES | TF_PLAN)                                      \
    X(TC_g, "g", TA_STEP, TF_MOVES)                                                \
    X(TC_LEFT, "+", TA_ANGLE, TF_TURNS | TF_PLAN)                                  \
    X(TC_RIGHT, "-", TA_ANGLE, TF_TURNS | TF_PLAN)                                 \
    X(TC_DOWN, "&", TA_ANGLE, TF_TURNS | TF_PLAN)                                  \
    X(TC_UP, "^", TA_ANGLE, TF_TURNS | TF_PLAN)                                    \
    X(TC_ROLL_LEFT, "\\", TA_ANGLE, TF_TURNS | TF_PLAN)                            \
    X(TC_ROLL_RIGHT, "/", TA_ANGLE, TF_TURNS | TF_PLAN)                            \
    X(TC_TURN_AROUND, "|", TA_NONE, TF_TURNS | TF_PLAN)                            \
    X(TC_LEVEL, "$", TA_NONE, TF_TURNS)                                            \
    X(TC_PUSH, "[", TA_NONE, TF_STACK | TF_PLAN)                                   \
    X(TC_POP, "]", TA_NONE, TF_STACK | TF_PLAN)                                    \
    X(TC_CUT, "%", TA_NONE, TF_STACK | TF_PLAN)                                    \
    X(TC_WIDTH, "!", TA_NONE, TF_STYLE | TF_PLAN)                                  \
    X(TC_MATERIAL, "'", TA_NONE, TF_STYLE | TF_PLAN)                               \
    X(TC_MATERIAL_NEXT, ";", TA_NONE, TF_STYLE)                                    \
    X(TC_MATERIAL_PREV, ",", TA_NONE, TF_STYLE)                                    \
    X(TC_POLY_OPEN, "{", TA_NONE, TF_DRAWS | TF_STEERS)                            \
    X(TC_VERTEX, ".", TA_NONE, TF_DRAWS)                                           \
    X(TC_POLY_CLOSE, "}", TA_NONE, TF_DRAWS | TF_STEERS)                           \
    X(TC_LEAF, "~leaf", TA_STEP, TF_DRAWS | TF_ORGAN | TF_PLAN)                    \
    X(TC_PETAL, "~petal", TA_STEP, TF_DRAWS | TF_ORGAN | TF_PLAN)                  \
    X(TC_NEEDLE, "~needle", TA_STEP, TF_DRAWS | TF_ORGAN | TF_PLAN)                \
    X(TC_SURFACE_UNKNOWN, NULL, TA_NONE, 0) /* warned about once, then ignored */ \
    X(TC_SPHERE, "@O", TA_WIDTH, TF_DRAWS | TF_ORGAN)                              \
    X(TC_DISC, "@c", TA_WIDTH, TF_DRAWS | TF_ORGAN)                                \
    X(TC_TROPISM, "@Tp", TA_NONE, TF_STEERS)                                       \
    X(TC_ELASTICITY, "@Ts", TA_ZERO, TF_STEERS)                                    \
    X(TC_MOVE_TO, "@M", TA_NONE, TF_MOVES)                                         \
    X(TC_HEADING, "@R", TA_NONE, TF_TURNS)                                         \
    X(TC_SCALE, "@D", TA_ONE, TF_STEERS)                                           \
    X(TC_SMOOTH_ON, "@Gc", TA_NONE, TF_STYLE)                                      \
    X(TC_SMOOTH_OFF, "@Ge", TA_NONE, TF_STYLE)                                     \
    X(TC_QUERY_P, "?P", TA_NONE, TF_QUERY)                                         \
    X(TC_QUERY_H, "?H", TA_NONE, TF_QUERY)                                         \
    X(TC_QUERY_L, "?L", TA_NONE, TF_QUERY)                                         \
    X(TC_QUERY_U, "?U", TA_NONE, TF_QUERY)                                         \
    X(TC_QUERY_E, "?E", TA_NONE, TF_QUERY)

/* Other names of the same commands: X(command, name). */
#define TURTLE_ALIASES(X) \
    X(TC_LEVEL, "@v")     \
    X(TC_PETAL, "~flower") \
    X(TC_SPHERE, "@o")     /* cpfg's filled circle: a sphere in 3D */ \
    X(TC_SMOOTH_ON, "@Gs")

typedef enum {
    TC_NONE, /* not a turtle symbol: the turtle ignores it */
#define TC_ENUM_(cmd, name, def, flags) cmd,
    TURTLE_COMMANDS(TC_ENUM_)
#undef TC_ENUM_
    TC_COUNT
} TurtleCommand;

/* The flags of a command (TC_NONE: none). */
static inline unsigned turtle_command_flags(unsigned cmd) {
#define TC_FLAGS_(cmd, name, def, flags) flags,
    static const uint16_t f[TC_COUNT] = {0, TURTLE_COMMANDS(TC_FLAGS_)};
#undef TC_FLAGS_
    return cmd < TC_COUNT ? f[cmd] : 0;
}

/* The default of a command's first parameter. */
static inline TurtleDefault turtle_command_default(unsigned cmd) {
#define TC_DEFAULT_(cmd, name, def, flags) def,
    static const uint8_t d[TC_COUNT] = {TA_NONE, TURTLE_COMMANDS(TC_DEFAULT_)};
#undef TC_DEFAULT_
    return cmd < TC_COUNT ? (TurtleDefault)d[cmd] : TA_NONE;
}

/* The command a module named `name` is (the compiler asks once per symbol). */
static inline TurtleCommand turtle_command_find(const char *name) {
    static const struct {
        const char *name;
        uint8_t cmd;
    } names[] = {
#define TC_NAME_(cmd, name, def, flags) {name, cmd},
#define TC_ALIAS_(cmd, name) {name, cmd},
        TURTLE_COMMANDS(TC_NAME_) TURTLE_ALIASES(TC_ALIAS_)
#undef TC_NAME_
#undef TC_ALIAS_
    };
    for (size_t k = 0; k < sizeof names / sizeof *names; k++)
        if (names[k].name && !strcmp(name, names[k].name)) return (TurtleCommand)names[k].cmd;
    return name[0] == '~' && name[1] ? TC_SURFACE_UNKNOWN : TC_NONE;
}

#endif
