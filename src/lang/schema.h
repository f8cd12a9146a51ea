/* The directive schema: a block's directives described as data (name, type, range, default,
 * unit, meaning, aliases), one table per kind, each written once as an X-macro .def in its
 * generator's folder (FOLDER/params.def, made into the table by FOLDER/schema.inc) or here
 * (lang/settings.def). This file is the one reader of those tables: a name's row (with a
 * level digit, an alias), did-you-mean, a value as a number or `(expr)`, its range, an enum's
 * word, and `--set NAME=VALUE` checked against the row. `sylva describe` (describe.c) and the
 * generated reference (tools/gen-directives → docs/directives.md) read the same rows. */
#ifndef SYL_SCHEMA_H
#define SYL_SCHEMA_H
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "sylva/sylva.h"

/* The types, as `sylva describe --json` names them. */
#define SCH_TYPES(X) X(NUMBER, "number") X(INTEGER, "integer") X(BOOLEAN, "boolean") X(ENUM, "enum") \
    X(LIST, "list") X(CURVE, "curve") X(FILE, "file") X(STRING, "string") X(VECTOR, "vector")
typedef enum {
#define X(t, s) SCH_##t,
    SCH_TYPES(X)
#undef X
} SchType;
const char *sch_type_name(SchType t);

typedef struct SchRow {
    const char *name;
    SchType type;
    double lo, hi;          /* the accepted range (numbers, integers, a list's elements); ±inf: unbounded */
    bool lo_open, hi_open;  /* the bound itself is excluded */
    int levels;             /* a list per level: how many levels (0: not per level) */
    double def[4];          /* the default (per level: one a level); NAN: none */
    const char *def_text;   /* the default of an enum, file or string; NULL: none */
    const char *words;      /* an enum's words, "a|b|c"; NULL otherwise */
    const char *unit;       /* "" when none */
    const char *doc;        /* one line */
    const char *aliases;    /* other names, "a|b"; NULL: none */
    const char *group;      /* the rows it belongs with (an ecosystem species': "species"); NULL: the block */
    /* The shape of a keyed line (SCH_KEYED, below): what a row DIRECTIVE of type enum (its
     * modes) or DIRECTIVE.KEY says of the line beyond its value. */
    const char *when;       /* a key: read only in this mode of its directive ("shadow"); NULL: every mode */
    const char *implied;    /* a mode: the one a line of keys only is in (`light voxel 0.3`: "shadow") */
    bool required;          /* a mode (or implied) must be written: `light` alone is wrong */
    const char *counted;    /* a mode word a whole number follows (`whorled 3`), */
    int count_lo, count_hi; /* within these, */
    const char *count_of;   /* counting these ("buds") */
    int repeat;             /* the directive may be given this many times, each line its own group */
    const char *symbols;    /* symbols ~S(x) a repeated line may carry, "S=MODE|...": the mode, */
    const char *symbol_key; /* and x (above 0) this key's value */
} SchRow;

/* How a block's lines give the rows their values (what `sylva describe` reads them by). */
typedef enum {
    SCH_SETTINGS, /* an lsystem's settings, kept in the program */
    SCH_LINES,    /* NAME VALUE... (weber, strands, curvetree, pafco), read by sch_read_lines */
    SCH_GROUPS,   /* NAME VALUE..., a group's rows after its opening line (ecosystem: species NAME) */
    SCH_KEYED,    /* DIRECTIVE [MODE [N]] [VALUE] [KEY VALUE]...: rows DIRECTIVE and DIRECTIVE.KEY (grow),
                   * read by sch_read_keyed */
    SCH_SCENE,    /* a scene's lines (scene/params.def): plant and obstacle lines, each an element of
                   * its group, at (x, y, z) its rows .x .y .z; read by scene/spec.c, described here */
} SchShape;

typedef struct SchTable {
    const char *kind;  /* "weber", "strands", ... */
    const char *noun;  /* what a row is: "setting", "parameter", "directive" */
    const SchRow *rows;
    int n;
    SchShape shape;
    const char *intro; /* docs/directives.md's paragraph about the table */
} SchTable;

/* The tables, defined by schema_tables.c: the lsystem's settings, and one for each kind with
 * directives (sch_grow, sch_weber, ...), written in its folder (FOLDER/schema.inc) and
 * declared here from the list of them in lang/kinds.def. */
extern const SchTable sch_lsystem;
#define SCH_TABLE(var, kind, noun, rows, shape, intro) extern const SchTable var;
#define SYL_KIND(...)
#define SYL_KIND_SCHEMAS
#include "lang/kinds.def"
#undef SYL_KIND_SCHEMAS
#undef SYL_KIND
#undef SCH_TABLE

/* The row of a directive name: the name, an alias, or a per-level name with its level digit
 * ("1DownAngle": *level 1); *level -1 when none. NULL: no such row. group NULL: any row. */
const SchRow *sch_find(const SchTable *t, const char *name, int *level);
/* " (did you mean 'a' or 'b'?)" for a name the table lacks (level digits kept), or "". */
void sch_suggest(const SchTable *t, const char *typed, char *buf, size_t size);
/* The same for a word of an enum row ("disc|square"), or "". */
void sch_suggest_word(const char *words, const char *typed, char *buf, size_t size);
/* The index of word among an enum's words, -1 if absent. */
int sch_word_index(const char *words, const char *word);

/* A number written plainly or as (expr) (which arrives evaluated as a one-value tuple). */
bool sch_number(const SylDirArg *a, double *x);
/* "[0, 1]", "(0, inf)", … */
void sch_range_text(const SchRow *r, char *buf, size_t size);
/* Whether x is allowed in r (range, whole for integers); when not, why ("must be in [0, 9],
 * not 12" / "takes a whole number in [0, 9], not 2.5") into why. */
bool sch_value_ok(const SchRow *r, double x, char *why, size_t size);

/* --set NAME=VALUE for a block of kind t: checks that name (within the model) is a row that
 * takes a number and that value is in its range; reports to diag as "--set TYPED: ..." and
 * returns 1, or returns 0 and sets *row, *level. */
int sch_set_check(const SylProgram *p, FILE *diag, const SchTable *t, const char *typed, const char *name,
                  double value, const SchRow **row, int *level);
/* The same, to p's sink, else sink. */
int sch_set_check_to(const SylProgram *p, const SylSink *sink, const SchTable *t, const char *typed, const char *name,
                     double value, const SchRow **row, int *level);

/* ---- Reading a keyed table's block (schema_keyed.c) ----
 * A row's value goes to a slot of the kind's parameter struct (or of the repeated line's
 * element, for the rows of a group): how it is stored, and where. */
typedef enum {
    SCH_AT_NONE,  /* not stored (a mode with no field) */
    SCH_AT_F32,
    SCH_AT_INT,
    SCH_AT_U64,   /* a whole number up to 2^53 (a seed) */
    SCH_AT_BOOL,
    SCH_AT_U8,    /* an enum's value in a byte */
    SCH_AT_F32X3, /* a vector */
    SCH_AT_TEXT,  /* a name, into char[size] */
    SCH_AT_F64,   /* a double; per level (a row with levels): double[4], level l at [l] */
    SCH_AT_I64,   /* a whole number into an int64_t */
    SCH_AT_LINE,  /* a file row: the line naming it (const SylDirective *) */
    SCH_AT_KIND,  /* read by the kind's own hook (SchLines.line, .set): a curve, a factor */
} SchStore;

typedef struct SchSlot {
    SchStore store;
    size_t off, size;  /* size: SCH_AT_TEXT's buffer */
    const int *values; /* an enum: the value stored for each word (NULL: its index) */
} SchSlot;
/* v into slot s of base, as its store says (a per-level number at level; other stores,
 * and s or base NULL: nothing). Both readers store through it. */
void sch_slot_store(const SchSlot *s, void *base, int level, double v);

/* A repeated line (its head row has repeat): where its elements are kept in base. */
typedef struct SchGroup {
    const char *dir;             /* the directive ("organ") */
    size_t off, size, count_off; /* the elements' array, an element's size, their count (an int) */
} SchGroup;

typedef struct SchKeyed {
    const SchTable *t;
    const SchSlot *slots; /* slots[i] is t->rows[i]'s; rows past nslots are not stored (texture lines) */
    int nslots;
    const SchGroup *groups; /* one per repeated directive of the table */
    int ngroups;
    /* a mode word was read (index word of row's words, count the whole number after it):
     * what else it sets (whorled 3: three buds a node). NULL: nothing */
    void (*mode_read)(void *base, const SchRow *row, int word, int count);
} SchKeyed;

/* Every row's default into base (the non-group rows; sch_keyed_group_defaults for an element
 * of group g). */
void sch_keyed_defaults(const SchKeyed *k, void *base);
void sch_keyed_group_defaults(const SchKeyed *k, const SchGroup *g, void *elem);
/* Read p's block over base (defaults already there): every line against its rows, with
 * file:line:col errors, then p's --set NAME=VALUE (DIRECTIVE.KEY, a key by its name alone, a
 * bare value by its directive's name, GROUP.N.KEY). Returns the errors, *set_errors of them
 * about --set values. */
int sch_read_keyed(const SylProgram *p, const SchKeyed *k, void *base, FILE *diag, int *set_errors);

/* What `sylva describe` reads a keyed block by: the same reader, storing nothing, tells it each
 * value a row takes as it takes it (lines, then --set). */
typedef struct SchSeen {
    /* A repeated line's element begins (elem from 0, counted per directive; head: its row). */
    void (*element)(void *ctx, const SchRow *head, int elem);
    /* row took n numbers x (1, or 3 for a vector) or a word (an enum's, a name); elem: the
     * element of its repeated line, -1 for the block's rows (a LINES table's --set: the level,
     * -1 none). */
    void (*value)(void *ctx, const SchRow *row, int elem, const double *x, int n, const char *word);
    void *ctx;
    /* A LINES table's line d gives row (at level, -1: none) its values as written. */
    void (*line)(void *ctx, const SchRow *row, int level, const SylDirective *d);
} SchSeen;
/* Read p's block (already checked: errors are counted, not reported) for seen. */
int sch_see_keyed(const SylProgram *p, const SchTable *t, const SchSeen *seen);

/* ---- Reading a LINES table's block (schema_lines.c) ----
 *   NAME VALUE...      (strands, curvetree, pafco, weber; `1DownAngle 60`, `DownAngle 0 60 45 45`)
 * Each line against its row (a name, an alias, a level digit), its values against the row's
 * type and range, stored through the row's slot; then --set NAME=VALUE. What is wrong is the
 * reader's to find and place (file:line:col); how it is worded is the kind's (SchLines.say),
 * so that each kind keeps its own messages. */
typedef enum {
    SCH_BAD_UNKNOWN,  /* no row of that name (hint: did-you-mean) */
    SCH_BAD_TWICE,    /* given again (line: the first) */
    SCH_BAD_LEVEL,    /* a level above 3 (5DownAngle) */
    SCH_BAD_COUNT,    /* not as many values as the row takes (most: how many it takes at most) */
    SCH_BAD_NUMBER,   /* a value that is no number */
    SCH_BAD_RANGE,    /* a number out of the row's range (why) */
    SCH_BAD_WORD,     /* not a word of the enum (hint) or not a word at all */
    SCH_BAD_FILE,     /* a file name not in quotes */
    SCH_BAD_SET_UNKNOWN,    /* --set of no row (hint) */
    SCH_BAD_SET_LEVELS,     /* --set of a per-level row without its level */
    SCH_BAD_SET_LEVEL,      /* --set of level above 3 */
    SCH_BAD_SET_NOT_NUMBER, /* --set of a row that is no number */
    SCH_BAD_SET_RANGE,      /* --set of a number out of range (why) */
    SCH_BAD_SET_ELEMENT,    /* --set ELEM.NAME of no element ELEM (name: ELEM; hint) */
    SCH_BAD_SET_NOT_GROUP,  /* --set ELEM.NAME of a row of the block's, not the group's */
} SchBad;

typedef struct SchProblem {
    SchBad what;
    const SylDirective *d;  /* the line (NULL: --set) */
    const SchRow *row;      /* NULL: unknown */
    const SylDirArg *at;    /* the caret's value (NULL: the line's name); say may move it */
    const char *name;       /* as written: a line's name or --set's (1DownAngle) */
    const char *typed;      /* --set's NAME as typed on the command line */
    const char *block;      /* the block's name */
    const char *shown;      /* the value's name with its level (1DownAngle of `DownAngle 0 60`) */
    const char *why;        /* RANGE: sch_value_ok's "must be in [0, 1], not 2" */
    const char *hint;       /* " (did you mean ...?)" or "" */
    double x;               /* the number (RANGE, --set) */
    int line, most;         /* TWICE: the first line; COUNT: the most values */
    bool lenient;           /* a value's problem is a warning: the default is kept */
    bool in_group;          /* UNKNOWN: the line follows a group's head (a species' line) */
} SchProblem;

typedef struct SchLineRead SchLineRead;

typedef struct SchLines {
    const SchTable *t;
    const SchSlot *slots; /* slots[i] is t->rows[i]'s; rows past nslots are not stored (texture lines) */
    int nslots;
    bool textures; /* the table's texture lines are lang/textures.c's: skipped */
    bool again;    /* a line may be given again (a `from` splice's, then the block's): the last wins;
                    * else a row is given once (a per-level row's lines are one row's) */
    /* The words of a problem (buf left empty: the reader's own). */
    void (*say)(SchProblem *pr, char *buf, size_t size);
    /* A row of slot SCH_AT_KIND: its line, and a --set of it (checked as a number of its row's
     * range by then); return the errors reported otherwise (sch_lines_error counts its own). */
    int (*line)(SchLineRead *r, const SchRow *row, const SylDirective *d, void *base);
    int (*set)(SchLineRead *r, const SchRow *row, const char *typed, double v, void *base);
    /* After the lines, before --set (the checks of what must be given); NULL: none. */
    int (*lines_done)(SchLineRead *r, void *base);
    /* After --set (what follows from what was given, sch_lines_took); NULL: none. */
    int (*done)(SchLineRead *r, void *base);
    /* row's value was stored (by a line or --set): what else that says (has_seed); NULL: nothing */
    void (*took)(void *base, const SchRow *row);
    /* Whether bad values of p's block are warnings, their defaults kept (a Pafčo file). */
    bool (*lenient)(const SylProgram *p);
    /* GROUPS (ecosystem): a line of group.dir (`species NAME`) opens an element, given by open
     * (NULL: none, the error reported); the rows of the table's group that follow are stored in
     * it, the others in base. --set NAME of a group's row sets it in every element, ELEM.NAME in
     * the element called ELEM (its name a char[] at name_off). */
    struct {
        const char *dir;
        size_t off, size, count_off, name_off; /* the elements in base, their count (an int) */
        void *(*open)(SchLineRead *r, const SylDirective *d, void *base);
    } group;
    bool set_if_clean; /* --set is applied only to lines without errors */
} SchLines;

/* Every row's default into base. */
void sch_lines_defaults(const SchLines *k, void *base);
/* Read p's block over base (defaults already there). Returns the errors, *set_errors of them
 * about --set values. */
int sch_read_lines(const SylProgram *p, const SchLines *k, void *base, FILE *diag, int *set_errors);
/* The same with its errors to sink (p's own when it has one), not a stream. */
int sch_read_lines_to(const SylProgram *p, const SchLines *k, void *base, const SylSink *sink, int *set_errors);
/* The same, storing nothing (describe's): told each line and --set value. */
int sch_see_lines(const SylProgram *p, const SchTable *t, const SchSeen *seen);
/* For a kind's hooks: the program, the sink, the line that gave row i (NULL: none yet), and an
 * error at d (a: the caret's value) counted in the reading. */
const SylProgram *sch_lines_program(const SchLineRead *r);
FILE *sch_lines_diag(const SchLineRead *r);
const SylDirective *sch_lines_given(const SchLineRead *r, int row);
int sch_lines_errors(const SchLineRead *r);
/* In the done hook: how many of the errors were --set's. */
int sch_lines_set_errors(const SchLineRead *r);
/* Whether row i was given, by a line or by --set. */
bool sch_lines_took(const SchLineRead *r, int row);
bool sch_lines_lenient(const SchLineRead *r);
/* The sink the errors go to (NULL: the stream's), and the end of the reading (nothing more is
 * read or checked: a limit passed). */
const SylSink *sch_lines_sink(const SchLineRead *r);
void sch_lines_stop(SchLineRead *r);
void sch_lines_error(SchLineRead *r, const SylDirective *d, const SylDirArg *a, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* The markdown of docs/directives.md: every table (describe.c). */
void lang_directives_reference(FILE *out);

/* A block is read once: its reader, called by the validate hook while syl_compile runs (one
 * thread, before the program is shared), keeps what it read in the program; a build then takes
 * that copy instead of reading the lines again. reads counts the full reads of the block (the
 * test that a block is read once, tests/unit/test_schema.c, looks at it). */
typedef struct SchCache {
    _Atomic int reads;
    void *value; /* malloc'd copy of the reader's result; NULL: none kept */
    size_t size;
    double lod;             /* the block's `lod` (lang_directive_lod), scanned once by syl_compile */
    bool lod_kept;
    _Atomic int lod_scans;  /* scans of the lines for `lod` */
    _Atomic int *also;      /* a program's count that this one's reads add to too (sch_count_into) */
} SchCache;
/* A full read of p's block begins. */
void sch_count_read(const SylProgram *p);
int sch_reads(const SylProgram *p);
int sch_lod_scans(const SylProgram *p);
/* q's reads count in p's too (a look compiled beside p's ecosystem: the test that a run reads
 * each block once counts them on the program it has); q is freed before p. */
void sch_count_into(const SylProgram *q, const SylProgram *p);
/* Keep size bytes at v as the block's reading (only while compiling: the validate hook). */
void sch_keep(const SylProgram *p, const void *v, size_t size);
/* The kept reading into out; false when there is none of that size. */
bool sch_kept(const SylProgram *p, void *out, size_t size);
/* A kind's block read once: read(p, params, diag, &set_errors) reads it in full into params
 * (size bytes) and returns its errors, set_errors of them about --set values. */
typedef int (*SchRead)(const SylProgram *p, void *params, FILE *diag, int *set_errors);
/* The build's reading: the one the check kept, or read now. Returns the errors. */
int sch_read_once(const SylProgram *p, void *params, size_t size, SchRead read, FILE *diag);
/* The check's (the validate hook): read, and keep a clean reading for the build. Returns the
 * errors, negative when every one was of a --set value. */
int sch_check_once(const SylProgram *p, void *params, size_t size, SchRead read, FILE *diag);

#endif
