/* libsylva: compile .syl models and derive their module strings.
 *
 * Every function reports problems as records to a sink (SylSink, below): the one its program
 * was compiled with, or the one it is given; or as text on the FILE * it is given
 * (diagnostics in the form `file:line:col: error: message`), and returns one of the SYL_*
 * status codes, which are also the exit codes of the `sylva` command. */
#ifndef SYLVA_H
#define SYLVA_H
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#define SYLVA_VERSION "0.1.0"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    SYL_OK = 0,
    SYL_EMODEL = 1, /* the model is wrong: syntax, names, or a runtime error in an expression */
    SYL_EUSAGE = 2, /* bad command line or option */
    SYL_ELIMIT = 3, /* a resource limit was hit (--max-modules, --max-memory) */
    SYL_EIO = 4,    /* a file could not be read or written */
    SYL_ECANCELED = 5, /* the caller's SylCancel asked to stop (never the sylva command's) */
};

typedef struct SylProgram SylProgram;
typedef struct SylString SylString;

/* Diagnostics as records, for a program that embeds the library: the library never writes to
 * stderr by itself. A diagnostic about a place in a model's source (its file, line and
 * column: the compile, the validation hook, and what the engines report later about its
 * lines) is made as a SylDiagnostic and handed to a sink: the one given in
 * SylCompileOptions.sink, else the text sink of the FILE * diag given, which writes it as
 * syl_diagnostic_write does (what `sylva` prints). Messages without a place (a file that
 * cannot be read, a limit) are records with no line and no path to the sink of the program
 * the call works on, else text on its FILE * diag; a function that works on no program (the
 * writers, the renderer, the terrain, the metrics, an ecosystem's run, checkpoint and MPI)
 * takes a sink itself, as an argument or beside the diag of its options (docs/embedding.md,
 * "Diagnostics"). */
typedef enum { SYL_DIAG_ERROR, SYL_DIAG_WARNING, SYL_DIAG_NOTE } SylSeverity;
typedef struct SylDiagnostic {
    SylSeverity severity;
    const char *path;        /* the file it is about; NULL: none (a message of the library's) */
    int line, column;        /* from 1, columns in bytes; 0: no place */
    const char *message;     /* without "error: "; controls shown escaped (^X, <U+XXXX>) */
    const char *source_line; /* the line at `line` as shown, tabs kept; NULL: not shown */
    int end_column;          /* the last byte column of the span on that line (>= column) */
    const char *caret;       /* the line under source_line marking the span ("  ^~~"), tabs
                                kept so that it lines up; NULL with source_line */
} SylDiagnostic;
typedef struct SylSink {
    void (*report)(void *user, const SylDiagnostic *d); /* the record lives during the call */
    void *user;
} SylSink;
/* The heavy libraries (Embree, libxml2, meshoptimizer, OpenMPI) are loaded when first used,
 * not at start-up. When one cannot be loaded, the library calls the handler given here, if
 * any (`sylva` reports it and exits with code 5), then aborts: there is no way back from the
 * middle of a call. soname: the library's file; what: what needs it; why: dlerror's reason.
 * One handler for the process; NULL removes it. */
typedef void SylMissingLibrary(const char *soname, const char *what, const char *why);
void syl_missing_library_set(SylMissingLibrary *handler);
/* The text form of d, as `sylva` prints it: `path:line:col: error: message`, then the source
 * line and the caret line under it. */
void syl_diagnostic_write(const SylDiagnostic *d, FILE *out);
/* The report of a text sink: writes d as syl_diagnostic_write does to the FILE * user, so
 * that `SylSink text = {syl_diagnostic_print, stderr}` prints what `sylva` prints. */
void syl_diagnostic_print(void *file, const SylDiagnostic *d);

/* A picture the library draws (a terrain's maps, an ecosystem's map): width x height RGB,
 * rows top to bottom, rgb malloc'ed; syl_picture_free frees it (and zeroes the struct). */
typedef struct SylPicture {
    uint8_t *rgb;
    int width, height;
} SylPicture;
void syl_picture_free(SylPicture *p);

/* A memory budget that several engines share, so that one limit (--max-memory) holds for a
 * whole run: derivation, growth, scenes, the mesher and the renderer each count their large
 * arrays against it and stop with SYL_ELIMIT, before allocating, when it would be passed.
 * Give the same budget to each engine's options (their `budget` field); NULL there: the
 * engine keeps its own, of its max_memory or the default (half the least of the machine's
 * memory, RLIMIT_AS, RLIMIT_DATA and the cgroup's memory limit, at most 16 GiB: docs/cli.md,
 * "The default memory budget"). Thread-safe. */
typedef struct SylBudget SylBudget;
SylBudget *syl_budget_new(uint64_t max_bytes); /* 0: the default; NULL when out of memory */
void syl_budget_free(SylBudget *b);
uint64_t syl_budget_used(const SylBudget *b);  /* bytes counted now */
uint64_t syl_budget_limit(const SylBudget *b);

/* A caller's way to stop a long build it no longer wants (a viewer whose file changed under
 * it): the engines ask stop(user) between their passes — before each derivation step, every
 * 65,536 modules the turtle reads, before every year a tree grows, before each Weber-Penn trunk
 * and main branch, every 4,096 strands segments, before a Pafco trunk and each whorl of its
 * crown, before a curvetree's trunk and each first-level branch, between the mesher's
 * planning and its writing — and on a nonzero answer free what they made and return
 * SYL_ECANCELED, saying nothing. Give the same
 * one to each engine's options (their `cancel` field; NULL: never). It is asked from the
 * calling thread only; a build it does not stop is the same as without it. */
typedef struct SylCancel {
    int (*stop)(void *user);
    void *user;
} SylCancel;
static inline int syl_cancelled(const SylCancel *c) { return c && c->stop && c->stop(c->user); }

typedef struct SylOverride {
    const char *name;
    double value;
} SylOverride;

/* The warnings a command that derives prints (`sylva check` prints every one). */
enum {
    SYL_WARN_MISTAKES = 1, /* a word close to a declared module; a rule for a parameter count
                              no string has; a grow block that grows nothing */
    SYL_WARN_DRAWS = 2,    /* a model that draws nothing (for the commands that draw) */
};

typedef struct SylCompileOptions {
    const char *model;            /* model name; NULL: the file's first lsystem */
    const SylOverride *overrides; /* --set name=value */
    int noverrides;
    FILE *diag;                   /* where diagnostics go; NULL: nowhere */
    int lint;                     /* also report warnings of `sylva check` (all of them) */
    int warn;                     /* or only these (SYL_WARN_*): mistakes that would pass silently */
    int sibling;                  /* compiled for another model of the file (a shoot rule, a
                                     scene's plant): --set names it lacks are not errors */
    /* What the language leaves to the engines that own it: syl_compile checks the language
     * only, then, once the program compiled without errors, calls validate (when not NULL)
     * with validate_user, the program and diag. It returns how many errors it reported to
     * diag; any fails the compile with SYL_EMODEL (a negative count: SYL_EUSAGE, errors of
     * the --set values only). syl_validate (below) checks every kind's directives and the
     * `scene` as `sylva check` reports them. A sibling compile passes none: its file was
     * checked with the model it serves. */
    int (*validate)(void *user, const SylProgram *p, FILE *diag);
    void *validate_user;
    /* The folders, besides the model file's own folder and what is below it, where the files
     * a model names (syl_program_file) may be (--allow-path); "/" allows every file. */
    const char *const *allow_paths;
    int nallow_paths;
    /* Where the program's diagnostics with a place go as records (above), instead of diag:
     * the compile's, the validation hook's, and those the engines report later about this
     * program's lines (syl_program_report_error, syl_directive_report_error), for as long as it lives; the
     * sink is copied. NULL: diag's text. Other models of the file compiled for this one
     * (syl_compile_model) report to their own diag. */
    const SylSink *sink;
} SylCompileOptions;

/* The validation hook for syl_compile (SylCompileOptions.validate; user: NULL, or an int *
 * that is not 0 to also warn about a scene's files that cannot be read, as `sylva check`
 * does — the commands that grow fail on them with an error of their own). It checks the
 * model's block as the engine of its kind reads it (grow, weber, strands, ecosystem: the
 * library's whole check, as `sylva check` runs it) and, for the file's first model (or a
 * file that holds only a scene), the `scene` block, including that each plant is of a kind
 * that can stand in a scene; each error with file:line:col, the source line and a caret.
 * Returns the number of errors, negative when every error was of a --set value. The engines
 * read the same directives, so a program compiled without the hook reports the same errors
 * there, when it is built. */
int syl_validate(void *user, const SylProgram *p, FILE *diag);

/* Compile source text (path is used in messages only). On failure *status is set and NULL
 * is returned; a NULL text reads the file at path ("-": standard input). The directives of
 * `grow` and `scene` blocks are read as values here and checked by opt->validate. */
SylProgram *syl_compile(const char *path, const char *text, size_t len, const SylCompileOptions *opt,
                        int *status);
void syl_program_free(SylProgram *p);
/* Another model of p's file, compiled from the same text with the same --set values (a
 * sibling compile: no validate hook). */
SylProgram *syl_compile_model(const SylProgram *p, const char *model, FILE *diag, int *status);
/* Read a whole file ("-": standard input), NUL-terminated, as syl_compile reads a NULL text
 * (a file utility, kept here for embedders); NULL with errno set on failure. Free with free(). */
char *syl_read_file(const char *path, size_t *len);
/* A file the model names (a weber block's `from` and `envelope`, a scene's `plant`, `obstacle`
 * and `ground`, an ecosystem's `terrain`): name relative to p's file's folder unless absolute,
 * into *path (malloc'd). Every reader of such a file calls this first: a file whose real path
 * (symlinks and `..` resolved) lies outside the model's own folder tree and the allowed
 * folders of SylCompileOptions.allow_paths is refused with SYL_EIO (errno EACCES) and
 * *path NULL; SYL_ELIMIT when out of memory. syl_file_refused says why, the same way
 * everywhere. */
int syl_program_file(const SylProgram *p, const char *name, char **path);
extern const char syl_file_refused[]; /* "outside the folders this model may read (...)" */
/* Whether text is recognisably a model (a block of the language, an Arbaro, Pícek, cpfg or
 * L-Py file): the lines of another file that a model names are shown in messages only then,
 * so that a model cannot print a file it names (`from "/etc/passwd"`). */
int syl_text_is_model(const char *text, size_t len);
/* Names of the models in a file, for listing; returns how many, writes at most max. */
int syl_model_list(const char *path, const char *text, size_t len, const char **names, int max,
                    char *buf, size_t bufsize);

/* What a compiled model is: an L-system, a `grow` block (self-organizing tree), — for a
 * file that holds only a `scene` block — the scene, a `weber` block (Weber–Penn parametric
 * tree), a `strands` block (Holton's strand model) or an `ecosystem` block (sylva/ecosystem.h).
 * The values are fixed; the library lists each kind once, with what it can do, in
 * src/lang/kinds.def (docs/architecture.md, "Adding a model kind"). */
typedef enum { SYL_MODEL_LSYSTEM = 0, SYL_MODEL_GROW = 1, SYL_MODEL_SCENE = 2, SYL_MODEL_WEBER = 3,
               SYL_MODEL_STRANDS = 4, SYL_MODEL_ECOSYSTEM = 5,
               SYL_MODEL_CURVETREE = 6, SYL_MODEL_PAFCO = 7 } SylModelKind;
/* "lsystem", "grow block", "scene", "weber block", "strands block", "ecosystem block"
 * (an ecosystem on a terrain: sylva/ecosystem.h) */
const char *syl_model_kind_name(SylModelKind k);
/* The keyword that opens its block: "lsystem", "grow", "scene", "weber", ... (NULL outside
 * the enum); the name bindings give a model's kind by. */
const char *syl_model_kind_keyword(SylModelKind k);
/* What a kind of model does, for a program (a binding) that must not keep a list of kinds:
 * SYL_MODEL_HAS_STRING, it is derived into a string of modules (`sylva derive`);
 * SYL_MODEL_HAS_STEPS, its steps are derivation steps or years of growth;
 * SYL_MODEL_IS_PLANT, syl_plant_build makes it (an ecosystem block is run instead).
 * 1 or 0 (0 outside the enum). */
typedef enum { SYL_MODEL_HAS_STRING, SYL_MODEL_HAS_STEPS, SYL_MODEL_IS_PLANT } SylModelTrait;
int syl_model_kind_is(SylModelKind k, SylModelTrait t);
/* Everything a kind can do, by name, for a front end that asks a question of its own (the
 * viewer's page, Python's Model.caps, the Blender add-on): syl_model_cap_name(i) for i from 0
 * until NULL is "rules", "string", "directives", "unnamed", "grows", "ages", "in_scene",
 * "look", "not_a_plant", "takes_trunk", "takes_envelope", "takes_terrain", "takes_obstacles"
 * (src/lang/kind_flags.def, the one list), syl_model_cap_doc(i) its one-line meaning, and
 * bit i of syl_model_kind_caps(k) whether kind k can (0 outside the enum). */
const char *syl_model_cap_name(int i);
const char *syl_model_cap_doc(int i);
unsigned syl_model_kind_caps(SylModelKind k);
SylModelKind syl_program_kind(const SylProgram *p);

/* The lines of a `grow` block (its directives) and of the file's `scene` block, with values
 * evaluated: numbers, words, strings, turtle symbols with parameters, and tuples. */
typedef enum { SYL_DARG_WORD, SYL_DARG_NUMBER, SYL_DARG_STRING, SYL_DARG_SYMBOL, SYL_DARG_TUPLE } SylDirArgKind;
typedef struct SylDirArg {
    SylDirArgKind kind;
    const char *text;     /* word, string, or symbol name (~leaf) */
    double num;           /* SYL_DARG_NUMBER */
    const double *values; /* SYL_DARG_TUPLE and the parameters of SYL_DARG_SYMBOL */
    int nvalues;
    int line, col;
} SylDirArg;
typedef struct SylDirective {
    const char *name;
    int line, col;
    const SylDirArg *args;
    int nargs;
    /* Where the line was written when not in the program's own source (a weber block's
     * `from "species.xml"`): that file's path and text, which line and col refer to;
     * NULL: the program's. */
    const char *file;
    const char *file_text;
    size_t file_len;
} SylDirective;
const SylDirective *syl_program_directives(const SylProgram *p, int *n); /* of a grow block */
const SylDirective *syl_program_scene(const SylProgram *p, int *n);      /* NULL: no scene */
/* Report an error about the program's source at line:col (0: none), with the source line
 * and a caret, in the form of every other diagnostic. */
void syl_program_report_error(const SylProgram *p, FILE *out, int line, int col, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));
/* An error about a directive's value a (NULL: about the directive's name), at its place:
 * directives may come from another file than the program's (a `weber` block's
 * `from "species.xml"`), and the message names that file and shows its line. */
void syl_directive_report_error(const SylProgram *p, FILE *out, const SylDirective *d, const SylDirArg *a,
                                const char *fmt, ...) __attribute__((format(printf, 5, 6)));
/* The path the program was read from (for files a model names, such as obstacles). */
const char *syl_program_path(const SylProgram *p);
/* The source text it was compiled from. */
const char *syl_program_source(const SylProgram *p, size_t *len);

const char *syl_program_name(const SylProgram *p);
int syl_program_steps(const SylProgram *p);        /* the model's `derive` */
uint64_t syl_program_seed(const SylProgram *p);
int syl_program_symbol_count(const SylProgram *p);
const char *syl_program_symbol_name(const SylProgram *p, int sym);
int syl_program_symbol_find(const SylProgram *p, const char *name); /* -1 if absent */
double syl_program_setting(const SylProgram *p, const char *name);  /* angle, step, width, derive, widthfactor, lod */

/* Functions a model declares `extern name(a, b)` (docs/language.md §6.5), which its caller
 * binds: fn(user, args, nargs, out) writes the value to *out and returns 0, or returns
 * nonzero for a failure (the derivation stops with SYL_EMODEL, the call's place reported).
 * The derivation's threads may call it at once. An extern left unbound runs its default body
 * (`extern f(x) = x`); a call to one without a default is an error. Bind before a
 * derivation of p starts, never while one runs. */
typedef int (*SylExternFn)(void *user, const double *args, int nargs, double *out);
int syl_program_extern_count(const SylProgram *p);
/* Extern i's name, its parameter count in *nparams and whether it has a default body (either
 * may be NULL); NULL when i is out of range. */
const char *syl_program_extern(const SylProgram *p, int i, int *nparams, int *has_default);
/* Bind fn (NULL: unbind) and user to the extern called name: SYL_OK, or SYL_EUSAGE when p
 * declares no extern of that name. */
int syl_program_bind_extern(SylProgram *p, const char *name, SylExternFn fn, void *user);
/* Print modules, constants, parameters, rules and their bytecode. */
void syl_program_dump(const SylProgram *p, FILE *out);

/* Environment queries (?E modules, docs/language.md "Open L-systems"): after every step the
 * turtle (syl_turtle_query, sylva/skeleton.h) reads the string and collects every segment's end and every ?E module with the
 * turtle's position and heading there; an environment then writes its answers into the
 * string's parameters: par[probe.par + k], k < probe.na. */
typedef struct SylEnvProbe {
    float pos[3], h[3];
    size_t par; /* offset of the module's parameters */
    int na;
    int tip;    /* nonzero: at the end of the segment just drawn (it casts shadow here too) */
} SylEnvProbe;
typedef struct SylEnvFill {
    float (*ends)[3]; /* segment ends, in the order drawn */
    size_t nends;
    SylEnvProbe *probes;
    size_t nprobes;
    struct SylEnvFillStore *store; /* the library's own (the arrays' room); start with {0},
                                      reuse across steps, free with syl_env_fill_free */
} SylEnvFill;
/* The kind an ?E module with parameters a[0..na) asks, its first parameter (none: light, 0):
 * bit k for kind k = 0 light, 1 crowding, 2 distance, 3 sky exposure; 0 for any other. */
static inline unsigned syl_env_kind_bit(const double *a, int na) {
    double kind = na ? a[0] : 0;
    return kind == 0 ? 1u : kind == 1 ? 2u : kind == 2 ? 4u : kind == 3 ? 8u : 0u;
}

/* Query modules (?P ?H ?L ?U ?E) are filled after every step (and after the axiom, step 0)
 * by an environment the caller plugs in: fill reads s as the turtle would (the engine has
 * applied the `interpret` rules already) and writes every query module's parameters in
 * place; the engine copies them back to the derived string. SYL_OK or a SYL_* error
 * (reported by the environment). */
typedef struct SylQueryOps {
    int (*fill)(void *user, const SylProgram *p, SylString *s, int step);
} SylQueryOps;

/* The stand-alone environment, `sylva derive`'s: the plant alone on the ground plane y = 0
 * under a sun overhead, shading and crowding itself (docs/language.md, "Open L-systems").
 * Install it with opt.queries = syl_env_standalone_ops(), opt.queries_user = the result of
 * syl_env_standalone_new(p, sink), for one derivation of p at a time; free it after the
 * derivation. Its errors (a shadow grid too large) go to sink (copied; NULL: nowhere). NULL
 * when out of memory. */
typedef struct SylEnvStandalone SylEnvStandalone;
SylEnvStandalone *syl_env_standalone_new(const SylProgram *p, const SylSink *sink);
void syl_env_standalone_free(SylEnvStandalone *e);
const SylQueryOps *syl_env_standalone_ops(void);

typedef struct SylDeriveOptions {
    int steps;            /* < 0: the model's `derive` */
    int use_seed;         /* nonzero: use seed instead of the model's */
    uint64_t seed;
    int threads;          /* <= 0: all cores */
    uint64_t max_modules; /* 0: default (200 million) */
    uint64_t max_memory;  /* bytes; 0: the default (syl_budget_new) */
    FILE *diag;
    /* Called with step 0 (the axiom, decomposed) and after every step; may be NULL. */
    void (*on_step)(void *user, int step, const SylString *s);
    void *user;
    uint64_t rewritten;   /* out: modules read by all passes of all steps (throughput) */
    /* The environment that fills query modules, and its user pointer; NULL: a stand-alone
     * one (the plant alone on the ground, shading itself), made and freed by the deriver. */
    const SylQueryOps *queries;
    void *queries_user;
    SylBudget *budget;    /* shared memory budget; NULL: one of max_memory */
    /* Stop with SYL_ELIMIT when all steps together would rewrite more than this many
     * modules (each pass counts as at least 100): a derivation that would run for hours.
     * 0: the default (100 billion). */
    uint64_t max_work;
    /* out: what the passes split among threads cost, in processor time of their threads (ns):
     * the chunks' sum and, per pass, the longest chunk's, summed; the same for the copies that
     * join them. On as many free cores as chunks, a pass takes its longest chunk: the schedule
     * `sylva derive --stats` and `make bench` model the speed-up of -j N with. */
    uint64_t split_passes, chunk_ns, chunk_max_ns, join_ns, join_max_ns;
    /* A pass is split among threads only when the last pass of its table cost at least this
     * many ns of processor time per module it read, times its growth (0: the default, 70;
     * docs/architecture.md, "Threads"): below it, the fresh memory and the join cost more
     * than the threads save. Once a split pass's chunks are seen to take as long side by side as
     * in turn (no free core), the rest of the derivation stays on one thread, unless split_ns
     * is given (nonzero: splits measured whatever the machine). */
    uint64_t split_ns;
    const SylCancel *cancel; /* asked before each step (above); NULL: never */
} SylDeriveOptions;

int syl_derive(const SylProgram *p, SylDeriveOptions *opt, SylString **out);
/* The same, a step at a time (a scene grows its L-systems year by year beside its trees):
 * begin reads the axiom — or start, when not NULL — and decomposes it (step 0); each
 * syl_derive_step derives one more step; end hands the string over (out may be NULL) and
 * frees the deriver. Every call returns SYL_OK or the error that stopped the derivation.
 * The deriver keeps opt (NULL: defaults): it must outlive the deriver. */
typedef struct SylDeriver SylDeriver;
int syl_derive_begin(const SylProgram *p, SylDeriveOptions *opt, const SylString *start, SylDeriver **out);
int syl_derive_step(SylDeriver *d);
const SylString *syl_deriver_string(const SylDeriver *d);
int syl_deriver_steps(const SylDeriver *d); /* steps derived so far */
int syl_derive_end(SylDeriver *d, SylString **out);
/* Apply the model's `interpret` rules: the string the turtle reads (never stored). */
int syl_interpret(const SylProgram *p, const SylString *in, const SylDeriveOptions *opt, SylString **out);

size_t syl_string_length(const SylString *s);
/* Module i: its symbol id, parameter count and a pointer to its parameters (valid until
 * the string changes). -1 (0 parameters, NULL) when i >= syl_string_length(s). Several
 * threads may read one string at once as long as none changes it. */
int syl_string_module(const SylString *s, size_t i, int *nparams, const double **params);
/* Canonical form: modules concatenated, parameters as %g separated by commas. */
int syl_string_write(const SylProgram *p, const SylString *s, FILE *out);
/* Count modules per symbol: counts must hold syl_program_symbol_count(p) entries. */
void syl_string_count(const SylString *s, uint64_t *counts);
/* Every module's symbol id, in order, into out (syl_string_length(s) entries). */
void syl_string_symbols(const SylString *s, int32_t *out);
/* The parameters of every module of symbol sym that has nparams of them, in string order, a
 * row of nparams after another into out (NULL: only count); returns how many rows. One pass,
 * for readers that want all the lengths of the Fs (the Python package's String.params). */
size_t syl_string_gather(const SylString *s, int sym, int nparams, double *out);
/* How many modules of symbol sym have k parameters, for k < SYL_MAX_PARAMS + 1, into counts. */
enum { SYL_MAX_PARAMS = 31 };
void syl_string_arities(const SylString *s, int sym, uint64_t counts[SYL_MAX_PARAMS + 1]);
void syl_string_free(SylString *s);
/* Every parameter of s, module after module (*n of them; NULL when there are none): where a
 * query environment writes its answers, at a SylEnvProbe's par. Valid until s changes. */
double *syl_string_params(SylString *s, size_t *n);
/* Build a string by hand (a derivation's start): an empty one, then modules appended. */
SylString *syl_string_new(void);
int syl_string_push(SylString *s, int sym, int nparams, const double *params);

#ifdef __cplusplus
}
#endif

#endif
