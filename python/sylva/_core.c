/* sylva._core: the CPython binding of libsylva (docs/python.md). It is thin on purpose: it
 * compiles, derives and builds through the public API, hands results to Python as buffers
 * (numpy views them without copying), and turns SYL_* statuses into exceptions. Everything
 * shaped for people (keyword arguments, tables, notebooks) is the Python package's. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sylva/ecosystem.h>
#include <sylva/grow.h>
#include <sylva/impostor.h>
#include <sylva/lod.h>
#include <sylva/metrics.h>
#include <sylva/plant.h>
#include <sylva/render.h>
#include <sylva/skeleton.h>
#include <sylva/stream.h>
#include <sylva/sylva.h>
#include <sylva/terrain.h>
#include <sylva/wind.h>
#if __has_include(<sylva/describe.h>)
#include <sylva/describe.h>
#define HAVE_DESCRIBE 1
#endif

/* The package's exception classes, handed over once by sylva/__init__.py (_set_errors). */
static PyObject *CompileError, *LimitError;

/* ---- diagnostics: the library writes them to a FILE *, here a memory stream ---- */

typedef struct Diag {
    char *buf;
    size_t len;
    FILE *f;
} Diag;

static int diag_open(Diag *d) {
    d->buf = NULL;
    d->len = 0;
    d->f = open_memstream(&d->buf, &d->len);
    if (!d->f) PyErr_NoMemory();
    return d->f ? 0 : -1;
}

static PyObject *diag_text(Diag *d) { /* closes the stream; a new str, or NULL */
    if (d->f) fclose(d->f);
    d->f = NULL;
    PyObject *s = PyUnicode_DecodeUTF8(d->buf ? d->buf : "", (Py_ssize_t)d->len, "replace");
    free(d->buf);
    d->buf = NULL;
    return s;
}

static void diag_drop(Diag *d) {
    if (d->f) fclose(d->f);
    free(d->buf);
    d->f = NULL;
    d->buf = NULL;
}

/* Raise the exception of a status, with the diagnostics as its message; returns NULL. */
static PyObject *raise_status(int status, Diag *d) {
    PyObject *text = diag_text(d);
    if (!text) return NULL;
    PyObject *cls = status == SYL_EMODEL ? CompileError
                    : status == SYL_ELIMIT ? LimitError
                    : status == SYL_EIO    ? PyExc_OSError
                                           : PyExc_ValueError;
    if (!cls) cls = PyExc_RuntimeError;
    /* the package's classes take the status too; Python's own take the message alone */
    int ours = cls == CompileError || cls == LimitError;
    PyObject *exc = ours ? PyObject_CallFunction(cls, "Oi", text, status) : PyObject_CallOneArg(cls, text);
    Py_DECREF(text);
    if (exc) {
        PyErr_SetObject(cls, exc);
        Py_DECREF(exc);
    }
    return NULL;
}

/* ---- Buffer: a read-only (or owned, writable) block of typed memory numpy can view ---- */

typedef struct {
    PyObject_HEAD
    PyObject *owner; /* keeps the memory alive; NULL when the buffer owns data */
    void *data;
    int owns;
    char format[4];
    Py_ssize_t itemsize;
    int ndim;
    Py_ssize_t shape[3], strides[3];
} BufferObject;

static void buffer_dealloc(BufferObject *b) {
    if (b->owns) free(b->data);
    Py_XDECREF(b->owner);
    Py_TYPE(b)->tp_free((PyObject *)b);
}

static int buffer_get(BufferObject *b, Py_buffer *view, int flags) {
    if ((flags & PyBUF_WRITABLE) && !b->owns) {
        PyErr_SetString(PyExc_BufferError, "this array is a read-only view of Sylva's memory");
        return -1;
    }
    Py_ssize_t n = b->itemsize;
    for (int i = 0; i < b->ndim; i++) n *= b->shape[i];
    view->obj = (PyObject *)b;
    Py_INCREF(b);
    view->buf = b->data;
    view->len = n;
    view->readonly = !b->owns;
    view->itemsize = b->itemsize;
    view->format = (flags & PyBUF_FORMAT) ? b->format : NULL;
    view->ndim = b->ndim;
    view->shape = b->shape;
    view->strides = b->strides;
    view->suboffsets = NULL;
    view->internal = NULL;
    return 0;
}

static PyBufferProcs buffer_procs = {(getbufferproc)buffer_get, NULL};

static PyTypeObject BufferType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "sylva._core.Buffer",
    .tp_basicsize = sizeof(BufferObject),
    .tp_dealloc = (destructor)buffer_dealloc,
    .tp_as_buffer = &buffer_procs,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "typed memory for numpy.asarray",
};

/* A C-contiguous buffer of rows x cols items of format fmt (cols < 0: one dimension). With an
 * owner, data is Sylva's and stays read-only; without, the buffer owns data (malloc'd). */
static PyObject *buffer_new(PyObject *owner, void *data, const char *fmt, Py_ssize_t itemsize,
                            Py_ssize_t rows, Py_ssize_t cols) {
    BufferObject *b = PyObject_New(BufferObject, &BufferType);
    if (!b) {
        if (!owner) free(data);
        return NULL;
    }
    b->owner = owner;
    Py_XINCREF(owner);
    b->owns = owner == NULL;
    b->data = data;
    snprintf(b->format, sizeof b->format, "%s", fmt);
    b->itemsize = itemsize;
    b->ndim = cols >= 0 ? 2 : 1;
    b->shape[0] = rows;
    b->shape[1] = cols;
    b->strides[0] = itemsize * (cols > 0 ? cols : 1);
    b->strides[1] = itemsize;
    return (PyObject *)b;
}

/* ---- Program: one compiled model ---- */

/* A Python function bound to an `extern` of the model (syl_program_bind_extern). */
typedef struct PyExtern {
    PyObject *fn;
    struct ProgramObject *owner;
    const char *name; /* the program's */
} PyExtern;

typedef struct ProgramObject {
    PyObject_HEAD
    SylProgram *p;
    PyExtern *externs; /* one per extern of p, fn NULL where nothing is bound */
    int nexterns;
    PyObject *et, *ev, *etb; /* the first exception a bound function raised, until the call returns */
} ProgramObject;

static void program_dealloc(ProgramObject *o) {
    syl_program_free(o->p);
    for (int i = 0; i < o->nexterns; i++) Py_XDECREF(o->externs[i].fn);
    free(o->externs);
    Py_XDECREF(o->et), Py_XDECREF(o->ev), Py_XDECREF(o->etb);
    Py_TYPE(o)->tp_free((PyObject *)o);
}

/* The call of an extern: the GIL taken, the arguments as floats, the result through float().
 * After a first exception the later calls fail at once (the derivation is stopping). */
static int pyextern_call(void *user, const double *args, int nargs, double *out) {
    PyExtern *x = user;
    ProgramObject *o = x->owner;
    PyGILState_STATE g = PyGILState_Ensure();
    int rc = -1;
    if (!o->et) {
        enum { FEW = 8 };
        PyObject *few[FEW], **argv = nargs <= FEW ? few : PyMem_Malloc(sizeof *argv * (size_t)nargs);
        int made = 0;
        if (argv)
            for (; made < nargs; made++)
                if (!(argv[made] = PyFloat_FromDouble(args[made]))) break;
        PyObject *r = argv && made == nargs ? PyObject_Vectorcall(x->fn, argv, (size_t)nargs, NULL) : NULL;
        for (int i = 0; i < made; i++) Py_DECREF(argv[i]);
        if (argv != few) PyMem_Free(argv);
        if (!argv) PyErr_NoMemory();
        if (r) {
            double v = PyFloat_AsDouble(r);
            if (!(v == -1.0 && PyErr_Occurred())) *out = v, rc = 0;
            else if (PyErr_ExceptionMatches(PyExc_TypeError)) {
                PyErr_Clear();
                PyErr_Format(PyExc_TypeError, "the function bound to extern '%s' returned %s, not a number", x->name,
                             Py_TYPE(r)->tp_name);
            }
            Py_DECREF(r);
        }
        if (rc) PyErr_Fetch(&o->et, &o->ev, &o->etb);
    }
    PyGILState_Release(g);
    return rc;
}

/* Raise the exception a bound function raised during the call just made (true), if any. */
static int extern_raised(ProgramObject *o) {
    if (!o->et) return 0;
    PyErr_Restore(o->et, o->ev, o->etb);
    o->et = o->ev = o->etb = NULL;
    return 1;
}

static PyTypeObject ProgramType;

static int read_overrides(PyObject *list, SylOverride **out, int *n) {
    *out = NULL;
    *n = 0;
    if (!list || list == Py_None) return 0;
    PyObject *seq = PySequence_Fast(list, "overrides must be a sequence of (name, value) pairs");
    if (!seq) return -1;
    Py_ssize_t k = PySequence_Fast_GET_SIZE(seq);
    SylOverride *ov = k ? calloc((size_t)k, sizeof *ov) : NULL;
    if (k && !ov) {
        Py_DECREF(seq);
        PyErr_NoMemory();
        return -1;
    }
    for (Py_ssize_t i = 0; i < k; i++) {
        PyObject *pair = PySequence_Fast_GET_ITEM(seq, i);
        const char *name;
        double v;
        if (!PyArg_ParseTuple(pair, "sd;an override is a (name, number) pair", &name, &v)) {
            free(ov);
            Py_DECREF(seq);
            return -1;
        }
        ov[i].name = name; /* lives as long as the caller's list */
        ov[i].value = v;
    }
    Py_DECREF(seq);
    *out = ov;
    *n = (int)k;
    return 0;
}

static PyObject *core_compile(PyObject *self, PyObject *args, PyObject *kw) {
    static char *kwl[] = {"path", "text", "model", "overrides", "lint", "validate", NULL};
    const char *path, *text = NULL, *model = NULL;
    Py_ssize_t len = 0;
    PyObject *ovl = NULL;
    int lint = 0, validate = 1;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "s|z#zOpp", kwl, &path, &text, &len, &model, &ovl, &lint,
                                     &validate))
        return NULL;
    SylOverride *ov;
    int nov;
    if (read_overrides(ovl, &ov, &nov)) return NULL;
    Diag d;
    if (diag_open(&d)) {
        free(ov);
        return NULL;
    }
    SylCompileOptions o = {.model = model, .overrides = ov, .noverrides = nov, .diag = d.f, .lint = lint,
                           .warn = SYL_WARN_MISTAKES};
    if (validate) o.validate = syl_validate;
    int st = 0;
    SylProgram *p;
    Py_BEGIN_ALLOW_THREADS
    p = syl_compile(path, text, (size_t)len, &o, &st);
    Py_END_ALLOW_THREADS
    free(ov);
    if (!p) return raise_status(st ? st : SYL_EMODEL, &d);
    ProgramObject *po = PyObject_New(ProgramObject, &ProgramType);
    if (!po) {
        syl_program_free(p);
        diag_drop(&d);
        return NULL;
    }
    po->p = p;
    po->externs = NULL, po->nexterns = 0, po->et = po->ev = po->etb = NULL;
    PyObject *warn = diag_text(&d);
    if (!warn) {
        Py_DECREF(po);
        return NULL;
    }
    return Py_BuildValue("(NN)", po, warn);
}

static PyObject *core_models(PyObject *self, PyObject *args) {
    const char *path, *text = NULL;
    Py_ssize_t len = 0;
    if (!PyArg_ParseTuple(args, "s|z#", &path, &text, &len)) return NULL;
    enum { MAX = 256 };
    const char *names[MAX];
    char *buf = malloc(1 << 16);
    if (!buf) return PyErr_NoMemory();
    int n;
    Py_BEGIN_ALLOW_THREADS
    n = syl_model_list(path, text, (size_t)len, names, MAX, buf, 1 << 16);
    Py_END_ALLOW_THREADS
    if (n < 0) {
        free(buf);
        return PyErr_Format(PyExc_OSError, "%s: cannot read the models", path);
    }
    PyObject *l = PyList_New(0);
    for (int i = 0; l && i < n && i < MAX; i++) {
        PyObject *s = PyUnicode_FromString(names[i]);
        if (!s || PyList_Append(l, s)) Py_CLEAR(l);
        Py_XDECREF(s);
    }
    free(buf);
    return l;
}

/* mesh_edges(triangles, nverts) -> (edges (E, 2) int32, loop_edge (3n,) int32): each triangle
 * side once, in the order they first appear, and the edge of every loop (loop 3t + i runs from
 * corner i to corner i + 1): what Blender wants of a mesh it is given, found by one hash of
 * the sides here rather than by Blender's own search or a numpy sort (the add-on's largest
 * cost on a big tree). */
static PyObject *core_mesh_edges(PyObject *self, PyObject *args) {
    Py_buffer tb;
    Py_ssize_t nverts;
    if (!PyArg_ParseTuple(args, "y*n", &tb, &nverts)) return NULL;
    size_t nloops = (size_t)tb.len / 4;
    if (tb.len % 12 || nverts < 0 || (uint64_t)nverts > UINT32_MAX) {
        PyBuffer_Release(&tb);
        return PyErr_Format(PyExc_ValueError, "mesh_edges: %zd bytes are not triangles of 32-bit indices", tb.len);
    }
    const uint32_t *idx = tb.buf;
    size_t cap = 16;
    while (cap < 2 * nloops) cap <<= 1;
    uint64_t *key = malloc(cap * sizeof *key);
    int32_t *slot = malloc(cap * sizeof *slot), *edges = malloc(2 * sizeof *edges * (nloops + 1)),
            *loop_edge = malloc(sizeof *loop_edge * (nloops + 1));
    if (!key || !slot || !edges || !loop_edge) {
        free(key), free(slot), free(edges), free(loop_edge);
        PyBuffer_Release(&tb);
        return PyErr_NoMemory();
    }
    memset(slot, 0xff, cap * sizeof *slot); /* -1: empty */
    int shift = 64;
    for (size_t c = cap; c > 1; c >>= 1) shift--;
    size_t ne = 0, bad = 0;
    for (size_t l = 0; l < nloops; l++) {
        uint32_t a = idx[l], b = idx[l % 3 == 2 ? l - 2 : l + 1];
        bad |= a >= (uint64_t)nverts || b >= (uint64_t)nverts;
        uint64_t k = a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
        size_t h = (size_t)((k * 0x9E3779B97F4A7C15ull) >> shift);
        while (slot[h] >= 0 && key[h] != k) h = (h + 1) & (cap - 1);
        if (slot[h] < 0) {
            key[h] = k, slot[h] = (int32_t)ne;
            edges[2 * ne] = (int32_t)(k >> 32), edges[2 * ne + 1] = (int32_t)(k & 0xffffffffu);
            ne++;
        }
        loop_edge[l] = slot[h];
    }
    free(key), free(slot);
    PyBuffer_Release(&tb);
    if (bad) {
        free(edges), free(loop_edge);
        return PyErr_Format(PyExc_ValueError, "mesh_edges: an index is not below %zd vertices", nverts);
    }
    int32_t *fit = realloc(edges, 2 * sizeof *edges * (ne + 1));
    return Py_BuildValue("(NN)", buffer_new(NULL, fit ? fit : edges, "i", 4, (Py_ssize_t)ne, 2),
                         buffer_new(NULL, loop_edge, "i", 4, (Py_ssize_t)nloops, -1));
}

/* instance_quads(t, r, s) -> (4n, 3) float32: for instances of translations t (n, 3), unit
 * quaternions r (n, 4: x, y, z, w) and scales s (n, 3), the corners of a square per instance,
 * centred on T, sides s_x along R x and R y, corners (-,-) (+,-) (+,+) (-,+): the faces the
 * Blender add-on instances its leaf on (computed in double, as the add-on's numpy did). */
static PyObject *core_instance_quads(PyObject *self, PyObject *args) {
    Py_buffer tb, rb, sb;
    if (!PyArg_ParseTuple(args, "y*y*y*", &tb, &rb, &sb)) return NULL;
    size_t n = (size_t)tb.len / 12;
    PyObject *res = NULL;
    float *out = NULL;
    if (tb.len % 12 || (size_t)rb.len != 16 * n || (size_t)sb.len != 12 * n)
        PyErr_Format(PyExc_ValueError, "instance_quads: %zd, %zd and %zd bytes are not n x 3, 4 and 3 floats", tb.len,
                     rb.len, sb.len);
    else if (!(out = malloc(12 * sizeof *out * (n + 1))))
        PyErr_NoMemory();
    else {
        const float *t = tb.buf, *r = rb.buf, *sc = sb.buf;
        static const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
        for (size_t i = 0; i < n; i++) {
            double x = r[4 * i], y = r[4 * i + 1], z = r[4 * i + 2], w = r[4 * i + 3], a = sc[3 * i] / 2.0;
            double ax[3] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)};
            double ay[3] = {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)};
            for (int c = 0; c < 4; c++)
                for (int k = 0; k < 3; k++)
                    out[12 * i + 3 * c + k] = (float)(t[3 * i + k] + a * sx[c] * ax[k] + a * sy[c] * ay[k]);
        }
        res = buffer_new(NULL, out, "f", 4, (Py_ssize_t)(4 * n), 3);
    }
    PyBuffer_Release(&tb), PyBuffer_Release(&rb), PyBuffer_Release(&sb);
    return res;
}

/* PNG bytes of an (H, W, 4) uint8 picture, by the library's encoder (sylva/stream.h). */
static PyObject *core_png_rgba(PyObject *self, PyObject *args) {
    Py_buffer px;
    int width, height;
    if (!PyArg_ParseTuple(args, "y*ii", &px, &width, &height)) return NULL;
    if (width <= 0 || height <= 0 || px.len != (Py_ssize_t)width * height * 4) {
        PyBuffer_Release(&px);
        return PyErr_Format(PyExc_ValueError, "png_rgba: %zd bytes are not %d x %d RGBA", px.len, width, height);
    }
    Diag d;
    char *buf = NULL;
    size_t len = 0;
    FILE *out = diag_open(&d) ? NULL : open_memstream(&buf, &len);
    if (!out) {
        diag_drop(&d);
        PyBuffer_Release(&px);
        return PyErr_NoMemory();
    }
    int st;
    Py_BEGIN_ALLOW_THREADS
    st = syl_png_write_rgba_stream(out, px.buf, width, height, &(SylSink){syl_diagnostic_print, d.f});
    Py_END_ALLOW_THREADS
    fclose(out);
    PyBuffer_Release(&px);
    PyObject *r = st ? raise_status(st, &d) : PyBytes_FromStringAndSize(buf, (Py_ssize_t)len);
    if (!st) diag_drop(&d);
    free(buf);
    return r;
}

static PyObject *program_info(ProgramObject *o, PyObject *unused) {
    const SylProgram *p = o->p;
    int nsym = syl_program_symbol_count(p);
    PyObject *syms = PyList_New(nsym);
    if (!syms) return NULL;
    for (int i = 0; i < nsym; i++) {
        PyObject *s = PyUnicode_FromString(syl_program_symbol_name(p, i));
        if (!s) {
            Py_DECREF(syms);
            return NULL;
        }
        PyList_SET_ITEM(syms, i, s);
    }
    SylModelKind k = syl_program_kind(p);
    PyObject *caps = PyDict_New(); /* {name: bool} of every capability the library lists */
    for (int i = 0; caps && syl_model_cap_name(i); i++)
        if (PyDict_SetItemString(caps, syl_model_cap_name(i), (syl_model_kind_caps(k) >> i & 1) ? Py_True : Py_False))
            Py_CLEAR(caps);
    if (!caps) {
        Py_DECREF(syms);
        return NULL;
    }
    return Py_BuildValue("{s:s,s:s,s:s,s:O,s:O,s:O,s:i,s:K,s:N,s:s,s:N}", "name", syl_program_name(p), "kind",
                         syl_model_kind_keyword(k), "kind_name", syl_model_kind_name(k), "has_string",
                         syl_model_kind_is(k, SYL_MODEL_HAS_STRING) ? Py_True : Py_False, "has_steps",
                         syl_model_kind_is(k, SYL_MODEL_HAS_STEPS) ? Py_True : Py_False, "is_plant",
                         syl_model_kind_is(k, SYL_MODEL_IS_PLANT) ? Py_True : Py_False,
                         "steps", syl_program_steps(p), "seed", (unsigned long long)syl_program_seed(p),
                         "symbols", syms, "path", syl_program_path(p), "caps", caps);
}

/* [(name, nparams, has_default)] of the model's extern declarations */
static PyObject *program_externs(ProgramObject *o, PyObject *unused) {
    int n = syl_program_extern_count(o->p);
    PyObject *l = PyList_New(n);
    for (int i = 0; l && i < n; i++) {
        int np, def;
        const char *name = syl_program_extern(o->p, i, &np, &def);
        PyObject *t = Py_BuildValue("(siO)", name, np, def ? Py_True : Py_False);
        if (!t) Py_CLEAR(l);
        else PyList_SET_ITEM(l, i, t);
    }
    return l;
}

/* bind(name, fn): fn (None: nothing) answers the model's `extern name(...)` from now on. */
static PyObject *program_bind(ProgramObject *o, PyObject *args) {
    const char *name;
    PyObject *fn;
    if (!PyArg_ParseTuple(args, "sO", &name, &fn)) return NULL;
    if (fn != Py_None && !PyCallable_Check(fn))
        return PyErr_Format(PyExc_TypeError, "the function bound to '%s' is not callable", name);
    int n = syl_program_extern_count(o->p);
    if (!o->externs && n) {
        o->externs = calloc((size_t)n, sizeof *o->externs);
        if (!o->externs) return PyErr_NoMemory();
        o->nexterns = n;
    }
    for (int i = 0; i < n; i++) {
        if (strcmp(syl_program_extern(o->p, i, NULL, NULL), name)) continue;
        PyExtern *x = &o->externs[i];
        x->owner = o; /* borrowed: the program outlives its bindings */
        x->name = syl_program_extern(o->p, i, NULL, NULL);
        Py_XSETREF(x->fn, fn == Py_None ? NULL : Py_NewRef(fn));
        syl_program_bind_extern(o->p, name, x->fn ? pyextern_call : NULL, x);
        Py_RETURN_NONE;
    }
    return PyErr_Format(PyExc_ValueError, "model '%s' declares no extern function '%s'", syl_program_name(o->p), name);
}

static PyObject *program_setting(ProgramObject *o, PyObject *args) {
    const char *name;
    if (!PyArg_ParseTuple(args, "s", &name)) return NULL;
    return PyFloat_FromDouble(syl_program_setting(o->p, name));
}

static PyObject *program_describe(ProgramObject *o, PyObject *unused) {
#ifdef HAVE_DESCRIBE
    Diag d;
    if (diag_open(&d)) return NULL;
    int st = syl_describe_json(o->p, d.f);
    if (st) return raise_status(st, &d);
    return diag_text(&d);
#else
    Py_RETURN_NONE;
#endif
}

/* ---- String: a derived module string ---- */

typedef struct {
    PyObject_HEAD
    SylString *s;
    PyObject *program; /* for its symbol names */
    uint64_t rewritten;
    double seconds, cpu_seconds; /* the derivation's wall and processor time (every thread's) */
} StringObject;

static void string_dealloc(StringObject *o) {
    syl_string_free(o->s);
    Py_XDECREF(o->program);
    Py_TYPE(o)->tp_free((PyObject *)o);
}

static Py_ssize_t string_len(StringObject *o) { return (Py_ssize_t)syl_string_length(o->s); }

static PyObject *string_module(StringObject *o, PyObject *args) {
    Py_ssize_t i;
    if (!PyArg_ParseTuple(args, "n", &i)) return NULL;
    Py_ssize_t n = (Py_ssize_t)syl_string_length(o->s);
    if (i < 0) i += n;
    if (i < 0 || i >= n) return PyErr_Format(PyExc_IndexError, "module %zd of a string of %zd", i, n);
    int np;
    const double *par;
    int sym = syl_string_module(o->s, (size_t)i, &np, &par);
    if (np && !par) return PyErr_NoMemory();
    PyObject *t = PyTuple_New(np);
    for (int k = 0; t && k < np; k++) {
        PyObject *v = PyFloat_FromDouble(par[k]);
        if (!v) {
            Py_CLEAR(t);
            break;
        }
        PyTuple_SET_ITEM(t, k, v);
    }
    return t ? Py_BuildValue("(iN)", sym, t) : NULL;
}

static PyObject *string_symbols(StringObject *o, PyObject *unused) {
    size_t n = syl_string_length(o->s);
    int32_t *ids = malloc(n ? n * sizeof *ids : 1);
    if (!ids) return PyErr_NoMemory();
    syl_string_symbols(o->s, ids);
    return buffer_new(NULL, ids, "i", 4, (Py_ssize_t)n, -1);
}

/* gather(sym, nparams): the parameters of every module of sym as rows x nparams doubles;
 * nparams < 0: the count its modules have, a ValueError when they differ. */
static PyObject *string_gather(StringObject *o, PyObject *args) {
    int sym, np;
    if (!PyArg_ParseTuple(args, "ii", &sym, &np)) return NULL;
    if (np > SYL_MAX_PARAMS) return PyErr_Format(PyExc_ValueError, "a module has at most %d parameters", SYL_MAX_PARAMS);
    uint64_t counts[SYL_MAX_PARAMS + 1];
    Py_BEGIN_ALLOW_THREADS
    syl_string_arities(o->s, sym, counts);
    Py_END_ALLOW_THREADS
    if (np < 0) {
        int kinds = 0;
        char seen[160] = "";
        for (int k = 0; k <= SYL_MAX_PARAMS; k++)
            if (counts[k]) {
                np = k;
                size_t at = strlen(seen);
                snprintf(seen + at, sizeof seen - at, "%s%d", kinds++ ? " or " : "", k);
            }
        if (kinds > 1)
            return PyErr_Format(PyExc_ValueError, "the modules of this name have %s parameters in this string: "
                                "say which with nparams=", seen);
        if (np < 0) np = 0;
    }
    size_t rows = counts[np];
    double *out = malloc(rows && np ? rows * (size_t)np * sizeof *out : 1);
    if (!out) return PyErr_NoMemory();
    if (rows && np) {
        Py_BEGIN_ALLOW_THREADS
        syl_string_gather(o->s, sym, np, out);
        Py_END_ALLOW_THREADS
    }
    return buffer_new(NULL, out, "d", 8, (Py_ssize_t)rows, np);
}

static PyObject *string_text(StringObject *o, PyObject *unused) {
    Diag d;
    if (diag_open(&d)) return NULL;
    int st;
    Py_BEGIN_ALLOW_THREADS
    st = syl_string_write(((ProgramObject *)o->program)->p, o->s, d.f);
    Py_END_ALLOW_THREADS
    if (st) return raise_status(st, &d);
    return diag_text(&d);
}

static PyObject *string_stats(StringObject *o, PyObject *unused) {
    return Py_BuildValue("{s:K,s:d,s:d}", "rewritten", (unsigned long long)o->rewritten, "seconds", o->seconds,
                         "cpu_seconds", o->cpu_seconds);
}

static PyMethodDef string_methods[] = {
    {"module", (PyCFunction)string_module, METH_VARARGS, "module(i) -> (symbol id, parameters)"},
    {"symbols", (PyCFunction)string_symbols, METH_NOARGS, "every module's symbol id (int32 buffer)"},
    {"gather", (PyCFunction)string_gather, METH_VARARGS, "gather(sym, nparams=-1) -> rows x nparams doubles"},
    {"text", (PyCFunction)string_text, METH_NOARGS, "the string as `sylva derive` prints it"},
    {"stats", (PyCFunction)string_stats, METH_NOARGS, "modules rewritten and seconds"},
    {NULL, NULL, 0, NULL},
};

static PySequenceMethods string_seq = {.sq_length = (lenfunc)string_len};

static PyTypeObject StringType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "sylva._core.String",
    .tp_basicsize = sizeof(StringObject),
    .tp_dealloc = (destructor)string_dealloc,
    .tp_as_sequence = &string_seq,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_methods = string_methods,
    .tp_doc = "a derived module string",
};

/* ---- a Python function as the environment of an open L-system ---- */

/* After each step the turtle's query pass fills ?P ?H ?L ?U and lists the ?E modules; the
 * Python side (sylva._environment) gets them as arrays in one call per step and writes its
 * answers into the parameter array, which is copied back into the string. */
typedef struct PyEnv {
    PyObject *fn;    /* fn(step, positions, headings, params, nparams, tips, ends) */
    PyObject *et, *ev, *etb; /* an exception the function raised, kept until the step returns */
    size_t answered; /* ?E modules answered */
} PyEnv;

static PyObject *floats_of(const float (*v)[3], size_t n) {
    float *c = malloc(n ? n * sizeof *v : 1);
    if (!c) return PyErr_NoMemory();
    if (n) memcpy(c, v, n * sizeof *v);
    return buffer_new(NULL, c, "f", 4, (Py_ssize_t)n, 3);
}

static int pyenv_call(PyEnv *e, SylString *s, const SylEnvFill *f, int step) {
    size_t k = f->nprobes;
    int maxna = 0;
    for (size_t i = 0; i < k; i++)
        if (f->probes[i].na > maxna) maxna = f->probes[i].na;
    float(*pos)[3] = malloc(k ? k * sizeof *pos : 1), (*hd)[3] = malloc(k ? k * sizeof *hd : 1);
    double *par = calloc(k && maxna ? k * (size_t)maxna : 1, sizeof *par);
    int32_t *na = malloc(k ? k * sizeof *na : 1);
    uint8_t *tip = malloc(k ? k : 1);
    size_t npar;
    double *all = syl_string_params(s, &npar);
    if (!pos || !hd || !par || !na || !tip) {
        free(pos), free(hd), free(par), free(na), free(tip);
        PyErr_NoMemory();
        return -1;
    }
    for (size_t i = 0; i < k; i++) {
        const SylEnvProbe *pr = &f->probes[i];
        memcpy(pos[i], pr->pos, sizeof pos[i]);
        memcpy(hd[i], pr->h, sizeof hd[i]);
        na[i] = pr->na;
        tip[i] = (uint8_t)(pr->tip != 0);
        for (int j = 0; j < pr->na; j++) par[i * (size_t)maxna + (size_t)j] = all[pr->par + (size_t)j];
    }
    PyObject *bpos = buffer_new(NULL, pos, "f", 4, (Py_ssize_t)k, 3);
    PyObject *bhd = buffer_new(NULL, hd, "f", 4, (Py_ssize_t)k, 3);
    PyObject *bpar = buffer_new(NULL, par, "d", 8, (Py_ssize_t)k, maxna);
    PyObject *bna = buffer_new(NULL, na, "i", 4, (Py_ssize_t)k, -1);
    PyObject *btip = buffer_new(NULL, tip, "B", 1, (Py_ssize_t)k, -1);
    PyObject *bends = floats_of((const float(*)[3])f->ends, f->nends);
    PyObject *r = NULL;
    if (bpos && bhd && bpar && bna && btip && bends)
        r = PyObject_CallFunction(e->fn, "iOOOOOO", step, bpos, bhd, bpar, bna, btip, bends);
    if (r) { /* the answers, as the function left them in params */
        for (size_t i = 0; i < k; i++) {
            const SylEnvProbe *pr = &f->probes[i];
            for (int j = 0; j < pr->na; j++) all[pr->par + (size_t)j] = par[i * (size_t)maxna + (size_t)j];
        }
        e->answered += k;
    }
    Py_XDECREF(r);
    Py_XDECREF(bpos), Py_XDECREF(bhd), Py_XDECREF(bpar), Py_XDECREF(bna), Py_XDECREF(btip), Py_XDECREF(bends);
    return r ? 0 : -1;
}

static int pyenv_fill(void *user, const SylProgram *p, SylString *s, int step) {
    PyEnv *e = user;
    SylEnvFill f = {0};
    int st = syl_turtle_query(p, s, &f);
    if (!st) {
        PyGILState_STATE g = PyGILState_Ensure();
        if (pyenv_call(e, s, &f, step)) {
            st = SYL_EMODEL;
            if (!e->et) PyErr_Fetch(&e->et, &e->ev, &e->etb);
            else PyErr_Clear();
        }
        PyGILState_Release(g);
    }
    syl_env_fill_free(&f);
    return st;
}

static const SylQueryOps pyenv_ops = {pyenv_fill};

/* Derive step by step, the GIL released during each step and Ctrl-C looked at between them. */
static PyObject *program_derive(ProgramObject *o, PyObject *args, PyObject *kw) {
    static char *kwl[] = {"steps", "seed", "threads", "max_modules", "max_memory", "environment", NULL};
    int steps = -1, threads = 0;
    PyObject *seedo = Py_None, *envfn = Py_None;
    unsigned long long max_modules = 0, max_memory = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|iOiKKO", kwl, &steps, &seedo, &threads, &max_modules,
                                     &max_memory, &envfn))
        return NULL;
    if (envfn != Py_None && !PyCallable_Check(envfn)) return PyErr_Format(PyExc_TypeError, "environment is a function");
    PyEnv env = {.fn = envfn};
    Py_CLEAR(o->et);
    Py_CLEAR(o->ev);
    Py_CLEAR(o->etb); /* a stale one, of a call that failed otherwise */
    Diag d;
    if (diag_open(&d)) return NULL;
    SylDeriveOptions *opt = calloc(1, sizeof *opt); /* the deriver keeps it */
    if (!opt) {
        diag_drop(&d);
        return PyErr_NoMemory();
    }
    opt->steps = steps;
    opt->threads = threads;
    opt->max_modules = max_modules;
    opt->max_memory = max_memory;
    opt->diag = d.f;
    if (envfn != Py_None) {
        opt->queries = &pyenv_ops;
        opt->queries_user = &env;
    }
    if (seedo != Py_None) {
        opt->use_seed = 1;
        opt->seed = PyLong_AsUnsignedLongLongMask(seedo);
        if (PyErr_Occurred()) {
            free(opt);
            diag_drop(&d);
            return NULL;
        }
    }
    int target = steps < 0 ? syl_program_steps(o->p) : steps;
    SylDeriver *dv = NULL;
    int st;
    struct timespec t0, t1, c0, c1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c0);
    Py_BEGIN_ALLOW_THREADS
    st = syl_derive_begin(o->p, opt, NULL, &dv);
    Py_END_ALLOW_THREADS
    while (!st && syl_deriver_steps(dv) < target) {
        if (env.et || o->et) break;
        if (PyErr_CheckSignals()) { /* KeyboardInterrupt: free all, let it propagate */
            syl_derive_end(dv, NULL);
            free(opt);
            diag_drop(&d);
            return NULL;
        }
        Py_BEGIN_ALLOW_THREADS
        st = syl_derive_step(dv);
        Py_END_ALLOW_THREADS
    }
    SylString *s = NULL;
    int st2 = dv ? syl_derive_end(dv, st ? NULL : &s) : st;
    if (!st) st = st2;
    clock_gettime(CLOCK_MONOTONIC, &t1);
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c1);
    if (env.et || o->et) { /* the environment's or a bound function's own exception, as raised */
        syl_string_free(s);
        free(opt);
        diag_drop(&d);
        if (extern_raised(o) && env.et) PyErr_Clear(); /* both: the environment's is the first */
        if (env.et) PyErr_Restore(env.et, env.ev, env.etb);
        return NULL;
    }
    uint64_t rewritten = opt->rewritten;
    free(opt);
    if (st || !s) {
        syl_string_free(s);
        return raise_status(st ? st : SYL_ELIMIT, &d);
    }
    diag_drop(&d);
    StringObject *so = PyObject_New(StringObject, &StringType);
    if (!so) {
        syl_string_free(s);
        return NULL;
    }
    so->s = s;
    so->program = (PyObject *)o;
    Py_INCREF(o);
    so->rewritten = rewritten;
    so->seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    so->cpu_seconds = (double)(c1.tv_sec - c0.tv_sec) + 1e-9 * (double)(c1.tv_nsec - c0.tv_nsec);
    return (PyObject *)so;
}

/* ---- Plant: what syl_plant_build made (skeleton and mesh) ---- */

typedef struct {
    PyObject_HEAD
    SylPlant pl;
    /* what `sylva mesh --lod --impostor --billboards --wind` adds (build's realtime options) */
    SylLodChain lods; /* lods.n 0: none; level 0 is pl.mesh */
    SylImpostor imp;  /* billboards 0: none */
    SylWind wind;     /* njoints 0: none */
    SylMeshOptions mo; /* what the mesh was made with (diag NULL) */
} PlantObject;

static void plant_dealloc(PlantObject *o) {
    syl_lod_free(&o->lods);
    syl_impostor_free(&o->imp);
    syl_wind_free(&o->wind);
    syl_plant_free(&o->pl);
    Py_TYPE(o)->tp_free((PyObject *)o);
}

static PyTypeObject PlantType;

/* The levels of detail and the impostor's billboards of a built plant, as cmd_mesh.c makes
 * them: LOD0 is the plant's mesh (optimised in place), then lod - 1 geometric levels and the
 * billboards (with impostor or billboards), or lod geometric levels. */
static int realtime_levels(PlantObject *pl, const SylMeshOptions *mo, int lod, int impostor, int billboards,
                           int grid, int view, int threads, FILE *diag) {
    if (!pl->pl.mesh || !pl->pl.skeleton) return SYL_EUSAGE;
    int last_billboard = impostor || billboards;
    int geometric = (lod ? lod : 1) - (last_billboard ? 1 : 0);
    int st = syl_lod_build(pl->pl.skeleton, mo, pl->pl.mesh, geometric, &pl->lods);
    if (st) fprintf(diag, "sylva: error: cannot build the levels of detail (out of memory)\n");
    if (!st && last_billboard) {
        SylImpostorOptions io = {.grid = impostor ? grid : -1, .view = view, .billboards = billboards ? billboards : 3,
                                 .threads = threads, .diag = diag};
        st = syl_impostor_add_level(&pl->lods, pl->pl.skeleton, mo, &io, &pl->imp);
    }
    return st;
}

/* The wind's joints and animation of a plant meshed with vertex nodes (`sylva mesh --wind`). */
static int realtime_wind(PlantObject *pl, const SylMeshOptions *mo, const SylWindOptions *wo, FILE *diag) {
    const SylSkeleton *sk = pl->pl.skeleton;
    if (!pl->pl.mesh || !sk) return SYL_EUSAGE;
    if (!pl->pl.mesh->node) {
        fprintf(diag, "sylva: error: wind cannot skin this mesh: part of it is not the plant's (a scene's "
                      "obstacles)\n");
        return SYL_EUSAGE;
    }
    float *radius = malloc((sk->nnodes + 1) * sizeof *radius);
    int st = radius ? syl_mesh_radii(sk, mo, radius) : SYL_ELIMIT;
    if (!st) st = syl_wind_build(sk, radius, wo, &pl->wind);
    free(radius);
    if (st && st != SYL_ELIMIT) fprintf(diag, "sylva: error: cannot build the wind's joints (bad model)\n");
    return st;
}

static PyObject *program_build(ProgramObject *o, PyObject *args, PyObject *kw) {
    static char *kwl[] = {"until", "steps", "seed", "threads", "max_modules", "max_memory", "scene", "leaves",
                          "sides", "age", "one_sided", "optimize", "lod", "impostor", "billboards", "impostor_grid",
                          "impostor_view", "wind", "wind_dx", "wind_dz", "wind_seconds", "wind_levels", NULL};
    int until = SYL_PLANT_MESH, steps = -1, threads = 0, scene = 0, leaves = 0, sides = 0, one_sided = 0,
        optimize = 0, lod = 0, impostor = 0, billboards = 0, grid = 0, view = 0, wind_levels = 0;
    double age = 0, wind = 0, wdx = 0, wdz = 0, wsec = 0;
    PyObject *seedo = Py_None;
    unsigned long long max_modules = 0, max_memory = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|iiOiKKpiidppipiiiddddi", kwl, &until, &steps, &seedo, &threads,
                                     &max_modules, &max_memory, &scene, &leaves, &sides, &age, &one_sided,
                                     &optimize, &lod, &impostor, &billboards, &grid, &view, &wind, &wdx, &wdz, &wsec,
                                     &wind_levels))
        return NULL;
    if (until < SYL_PLANT_MESH || until > SYL_PLANT_STRING)
        return PyErr_Format(PyExc_ValueError, "until is 0 (mesh), 1 (skeleton) or 2 (string), not %d", until);
    if (age < 0 || age > 1) return PyErr_Format(PyExc_ValueError, "age is in [0, 1], not %g", age);
    /* the checks of `sylva mesh`'s options (cli/options.c), said as Python says them */
    if (lod < 0 || lod > SYL_LOD_MAX) return PyErr_Format(PyExc_ValueError, "lod is 0 to %d, not %d", SYL_LOD_MAX, lod);
    if (billboards && (billboards < 2 || billboards > 4))
        return PyErr_Format(PyExc_ValueError, "billboards is 2, 3 or 4, not %d", billboards);
    if (grid < 0 || view < 0 || wind < 0 || wsec < 0 || wind_levels < 0)
        return PyErr_Format(PyExc_ValueError, "impostor_grid, impostor_view, wind, wind_seconds and wind_levels are "
                                              "not negative");
    int levels = lod || impostor || billboards;
    if ((levels || wind > 0) && until != SYL_PLANT_MESH)
        return PyErr_Format(PyExc_ValueError, "lod, impostor, billboards and wind need the mesh (until='mesh')");
    Diag d;
    if (diag_open(&d)) return NULL;
    SylMeshOptions mo = {.leaves = leaves, .sides = sides, .threads = threads, .one_sided = one_sided, .diag = d.f,
                         .vertex_nodes = wind > 0};
    SylPlantOptions po = {.threads = threads, .max_modules = max_modules, .max_memory = max_memory,
                          .until = (SylPlantStage)until, .scene = scene, .age = age, .mesh = &mo, .diag = d.f};
    if (steps >= 0) {
        po.use_steps = 1;
        po.steps = steps;
    }
    if (seedo != Py_None) {
        po.use_seed = 1;
        po.seed = PyLong_AsUnsignedLongLongMask(seedo);
        if (PyErr_Occurred()) {
            diag_drop(&d);
            return NULL;
        }
    }
    PlantObject *pl = PyObject_New(PlantObject, &PlantType);
    if (!pl) {
        diag_drop(&d);
        return NULL;
    }
    Py_CLEAR(o->et);
    Py_CLEAR(o->ev);
    Py_CLEAR(o->etb);
    memset(&pl->pl, 0, sizeof pl->pl);
    memset(&pl->lods, 0, sizeof pl->lods);
    memset(&pl->imp, 0, sizeof pl->imp);
    memset(&pl->wind, 0, sizeof pl->wind);
    pl->mo = mo;
    pl->mo.diag = NULL;
    int st;
    Py_BEGIN_ALLOW_THREADS
    st = syl_plant_build(o->p, &po, &pl->pl);
    /* as `sylva mesh` does before it writes a file (no view of the arrays exists yet) */
    if (!st && levels) st = realtime_levels(pl, &mo, lod, impostor, billboards, grid, view, threads, d.f);
    else if (!st && optimize && pl->pl.mesh) st = syl_mesh_optimize(pl->pl.mesh);
    if (!st && wind > 0) {
        SylWindOptions wo = {.speed = (float)wind, .dir = {(float)wdx, (float)wdz}, .seconds = (float)wsec,
                             .levels = wind_levels, .diag = d.f};
        st = realtime_wind(pl, &mo, &wo, d.f);
    }
    Py_END_ALLOW_THREADS
    if (st) {
        Py_DECREF(pl);
        if (extern_raised(o)) {
            diag_drop(&d);
            return NULL;
        }
        return raise_status(st, &d);
    }
    diag_drop(&d);
    return (PyObject *)pl;
}

static PyObject *plant_info(PlantObject *o, PyObject *unused) {
    const SylPlant *p = &o->pl;
    return Py_BuildValue("{s:i,s:n,s:K,s:n,s:n,s:n,s:n,s:n,s:d,s:d,s:d,s:d}", "kind", (int)p->kind, "modules",
                         (Py_ssize_t)p->modules, "rewritten", (unsigned long long)p->rewritten, "nodes",
                         (Py_ssize_t)(p->skeleton ? p->skeleton->nnodes : 0), "organs",
                         (Py_ssize_t)(p->skeleton ? p->skeleton->norgans : 0), "polygons",
                         (Py_ssize_t)(p->skeleton ? p->skeleton->npolys : 0), "vertices",
                         (Py_ssize_t)(p->mesh ? p->mesh->nverts : 0), "triangles",
                         (Py_ssize_t)(p->mesh ? p->mesh->nidx / 3 : 0), "derive_s", p->derive_s, "turtle_s",
                         p->turtle_s, "mesh_s", p->mesh_s, "derive_cpu_s", p->derive_cpu_s);
}

static int need_skeleton(PlantObject *o) {
    if (o->pl.skeleton) return 0;
    PyErr_SetString(PyExc_ValueError, "this plant was built without a skeleton (until='string')");
    return -1;
}

static int need_mesh(PlantObject *o) {
    if (o->pl.mesh) return 0;
    PyErr_SetString(PyExc_ValueError, "this plant was built without a mesh (until='skeleton')");
    return -1;
}

/* The skeleton's node and organ records as raw bytes, one row a record: numpy views them with
 * the structured dtype of NODE_LAYOUT / ORGAN_LAYOUT (no copy). */
static PyObject *plant_nodes(PlantObject *o, PyObject *unused) {
    if (need_skeleton(o)) return NULL;
    SylSkeleton *s = o->pl.skeleton;
    return buffer_new((PyObject *)o, s->nodes, "B", 1, (Py_ssize_t)s->nnodes, (Py_ssize_t)sizeof(SylNode));
}

static PyObject *plant_organs(PlantObject *o, PyObject *unused) {
    if (need_skeleton(o)) return NULL;
    SylSkeleton *s = o->pl.skeleton;
    return buffer_new((PyObject *)o, s->organs, "B", 1, (Py_ssize_t)s->norgans, (Py_ssize_t)sizeof(SylOrgan));
}

/* A mesh's arrays as views kept alive by owner, which owns m (a plant: its mesh or a level's). */
static PyObject *mesh_dict(PyObject *owner, const SylMesh *m) {
    Py_ssize_t nv = (Py_ssize_t)m->nverts, nt = (Py_ssize_t)(m->nidx / 3);
    PyObject *groups = PyList_New(m->ngroups);
    for (int g = 0; groups && g < m->ngroups; g++) {
        const SylMeshGroup *gr = &m->groups[g];
        const SylMaterial *mat = &m->materials[gr->material];
        PyObject *t = Py_BuildValue("{s:I,s:I,s:i,s:(ddd),s:i}", "first", gr->first / 3, "count", gr->count / 3,
                                    "material", gr->material, "rgb", mat->rgb[0], mat->rgb[1], mat->rgb[2],
                                    "kind", mat->kind);
        if (!t) {
            Py_CLEAR(groups);
            break;
        }
        PyList_SET_ITEM(groups, g, t);
    }
    if (!groups) return NULL;
    return Py_BuildValue("{s:N,s:N,s:N,s:N,s:N}", "positions", buffer_new(owner, m->pos, "f", 4, nv, 3),
                         "normals", buffer_new(owner, m->nrm, "f", 4, nv, 3), "uvs",
                         buffer_new(owner, m->uv, "f", 4, nv, 2), "triangles",
                         buffer_new(owner, m->idx, "I", 4, nt, 3), "groups", groups);
}

static PyObject *plant_mesh_arrays(PlantObject *o, PyObject *unused) {
    if (need_mesh(o)) return NULL;
    return mesh_dict((PyObject *)o, o->pl.mesh);
}

/* [{level, max_order, ..., mesh: mesh_dict}] of the levels of detail, LOD0 first ([]: none). */
static PyObject *plant_levels(PlantObject *o, PyObject *unused) {
    PyObject *l = PyList_New(0);
    for (int k = 0; l && k < o->lods.n; k++) {
        const SylLodLevel *lv = &o->lods.level[k];
        int bb = o->imp.billboards && k == o->lods.n - 1;
        PyObject *mesh = mesh_dict((PyObject *)o, lv->mesh);
        PyObject *t = mesh ? Py_BuildValue("{s:i,s:i,s:d,s:d,s:d,s:d,s:d,s:d,s:O,s:N}", "level", k, "max_order",
                                           lv->max_order, "min_radius", (double)lv->min_radius, "leaf_keep",
                                           (double)lv->leaf_keep, "leaf_scale", (double)lv->leaf_scale,
                                           "cluster_leaves", (double)lv->cluster_leaves, "coverage",
                                           (double)lv->coverage, "error", (double)lv->error, "billboards",
                                           bb ? Py_True : Py_False, "mesh", mesh)
                           : NULL;
        if (!t || PyList_Append(l, t)) Py_CLEAR(l);
        Py_XDECREF(t);
    }
    return l;
}

/* The impostor's atlases and sphere (None: no impostor was baked). */
static PyObject *plant_impostor(PlantObject *o, PyObject *unused) {
    const SylImpostor *im = &o->imp;
    if (!im->billboards) Py_RETURN_NONE;
    PyObject *color = im->color ? buffer_new((PyObject *)o, im->color, "B", 1, im->size, (Py_ssize_t)im->size * 4)
                                : Py_NewRef(Py_None);
    PyObject *normal = im->normal ? buffer_new((PyObject *)o, im->normal, "B", 1, im->size, (Py_ssize_t)im->size * 4)
                                  : Py_NewRef(Py_None);
    PyObject *bb = buffer_new((PyObject *)o, im->bb_color, "B", 1, im->view, (Py_ssize_t)im->bb_width * 4);
    return Py_BuildValue("{s:i,s:i,s:i,s:N,s:N,s:(ddd),s:d,s:i,s:i,s:N}", "grid", im->color ? im->grid : 0, "view",
                         im->view, "size", im->color ? im->size : 0, "color", color, "normal", normal, "centre",
                         (double)im->centre[0], (double)im->centre[1], (double)im->centre[2], "radius",
                         (double)im->radius, "billboards", im->billboards, "bb_width", im->bb_width, "bb_color", bb);
}

/* The wind's stems and joints (raw records), key rotations and each vertex's two joints and
 * weights as the .glb skins them (None: no wind). */
static PyObject *plant_wind(PlantObject *o, PyObject *unused) {
    const SylWind *w = &o->wind;
    if (!w->njoints) Py_RETURN_NONE;
    return Py_BuildValue("{s:d,s:i,s:N,s:N,s:N}", "seconds", (double)w->seconds, "nkeys", w->nkeys, "stems",
                         buffer_new((PyObject *)o, w->stems, "B", 1, w->nstems, (Py_ssize_t)sizeof *w->stems),
                         "joints", buffer_new((PyObject *)o, w->joints, "B", 1, w->njoints,
                                              (Py_ssize_t)sizeof *w->joints),
                         "rot", buffer_new((PyObject *)o, w->rot, "f", 4, (Py_ssize_t)w->njoints * w->nkeys, 4));
}

/* skin(k): (joints, weights), each vertex's two of level k's mesh (0: the plant's) as the .glb
 * skins it; None without wind or for a level without vertex nodes (the billboards). */
static PyObject *plant_skin(PlantObject *o, PyObject *args) {
    int k = 0;
    if (!PyArg_ParseTuple(args, "|i", &k)) return NULL;
    if (k < 0 || (k > 0 && k >= o->lods.n)) return PyErr_Format(PyExc_IndexError, "no level %d", k);
    const SylMesh *m = k ? o->lods.level[k].mesh : o->pl.mesh;
    if (!o->wind.njoints || !m->node) Py_RETURN_NONE;
    int32_t *joints = malloc(2 * sizeof *joints * (m->nverts + 1));
    uint8_t *weights = malloc(2 * (m->nverts + 1));
    if (!joints || !weights) {
        free(joints), free(weights);
        return PyErr_NoMemory();
    }
    syl_wind_skin(m, o->pl.skeleton, &o->wind, joints, weights);
    return Py_BuildValue("(NN)", buffer_new(NULL, joints, "i", 4, (Py_ssize_t)m->nverts, 2),
                         buffer_new(NULL, weights, "B", 1, (Py_ssize_t)m->nverts, 2));
}

static void sets_free(PyObject *capsule) {
    int *n = PyCapsule_GetContext(capsule);
    syl_instances_free(PyCapsule_GetPointer(capsule, "sylva.instances"), n ? *n : 0);
    free(n);
}

/* Each instance's joint with wind (the heavier of the two at its place, the one the .glb puts
 * it under: glb_skin.c), from syl_wind_skin over the instances' translations and nodes; None
 * without wind. */
static PyObject *set_joints(PlantObject *o, const SylInstances *x) {
    if (!o->wind.njoints || !x->node) Py_RETURN_NONE;
    int32_t *two = malloc(2 * sizeof *two * (x->count + 1)), *one = malloc(sizeof *one * (x->count + 1));
    uint8_t *weights = malloc(2 * (x->count + 1));
    if (!two || !one || !weights) {
        free(two), free(one), free(weights);
        return PyErr_NoMemory();
    }
    SylMesh at = {.pos = x->t, .node = x->node, .nverts = x->count}; /* only pos, node and nverts are read */
    syl_wind_skin(&at, o->pl.skeleton, &o->wind, two, weights);
    for (size_t i = 0; i < x->count; i++) one[i] = two[2 * i];
    free(two), free(weights);
    return buffer_new(NULL, one, "i", 4, (Py_ssize_t)x->count, -1);
}

/* A list of set dicts {name, proto: mesh_dict, t, r, s, node, joint}, views kept alive by owner. */
static PyObject *sets_list(PlantObject *o, PyObject *owner, const SylInstances *sets, int n) {
    PyObject *l = PyList_New(0);
    for (int i = 0; l && i < n; i++) {
        const SylInstances *x = &sets[i];
        Py_ssize_t c = (Py_ssize_t)x->count;
        PyObject *t = Py_BuildValue("{s:s,s:N,s:N,s:N,s:N,s:N,s:N}", "name", x->name, "proto",
                                    mesh_dict(owner, x->proto), "t", buffer_new(owner, x->t, "f", 4, c, 3), "r",
                                    buffer_new(owner, x->r, "f", 4, c, 4), "s", buffer_new(owner, x->s, "f", 4, c, 3),
                                    "node", x->node ? buffer_new(owner, x->node, "i", 4, c, -1) : Py_NewRef(Py_None),
                                    "joint", set_joints(o, x));
        if (!t || PyList_Append(l, t)) Py_CLEAR(l);
        Py_XDECREF(t);
    }
    return l;
}

/* leaf_sets(cards=False, level=0): the leaves as instances of one prototype a leaf material, as
 * `sylva mesh --leaves instanced` (or instanced-cards) writes them into a .glb: [{name, proto:
 * mesh_dict, t, r, s, node, joint}] (translations, rotations x y z w, scales, each leaf's node
 * and, with wind, its joint). Level k >= 1: the sets the levels of detail were built with (a
 * plant built with leaves instanced or instanced-cards; else none), cards not asked. */
static PyObject *plant_leaf_sets(PlantObject *o, PyObject *args, PyObject *kw) {
    static char *kwl[] = {"cards", "level", NULL};
    int cards = 0, level = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|pi", kwl, &cards, &level)) return NULL;
    if (need_skeleton(o)) return NULL;
    if (level < 0 || (level > 0 && level >= o->lods.n)) return PyErr_Format(PyExc_IndexError, "no level %d", level);
    if (level > 0) {
        const SylLodLevel *lv = &o->lods.level[level];
        return sets_list(o, (PyObject *)o, lv->sets, lv->nsets);
    }
    Diag d;
    if (diag_open(&d)) return NULL;
    SylMeshOptions mo = o->mo;
    mo.leaves = cards ? SYL_LEAVES_INSTANCED_CARDS : SYL_LEAVES_INSTANCED;
    mo.one_sided = 1; /* a .glb's leaves: one face, drawn from both sides */
    mo.vertex_nodes = 1;
    mo.diag = d.f;
    SylInstances *sets = NULL;
    int n = 0, st;
    Py_BEGIN_ALLOW_THREADS
    st = syl_instances_build(o->pl.skeleton, &mo, &sets, &n);
    Py_END_ALLOW_THREADS
    if (st) return raise_status(st, &d);
    diag_drop(&d);
    int *count = malloc(sizeof *count);
    PyObject *cap = count ? PyCapsule_New(sets, "sylva.instances", sets_free) : NULL;
    if (!cap) {
        free(count);
        syl_instances_free(sets, n);
        return PyErr_Occurred() ? NULL : PyErr_NoMemory();
    }
    *count = n;
    PyCapsule_SetContext(cap, count);
    PyObject *l = sets_list(o, cap, sets, n);
    Py_DECREF(cap);
    return l;
}

static PyObject *plant_write(PlantObject *o, PyObject *args) {
    const char *path;
    if (!PyArg_ParseTuple(args, "s", &path)) return NULL;
    if (need_mesh(o)) return NULL;
    Diag d;
    if (diag_open(&d)) return NULL;
    int st;
    Py_BEGIN_ALLOW_THREADS
    SylMeshOutput out = {.mesh = o->pl.mesh, .lods = o->lods.n ? &o->lods : NULL, .skeleton = o->pl.skeleton,
                         .wind = o->wind.njoints ? &o->wind : NULL};
    SylSink sink = {syl_diagnostic_print, d.f};
    st = out.lods || out.wind ? syl_mesh_write_output(&out, path, &sink) : syl_mesh_write(o->pl.mesh, path, &sink);
    Py_END_ALLOW_THREADS
    if (st) return raise_status(st, &d);
    diag_drop(&d);
    Py_RETURN_NONE;
}

static PyObject *plant_skeleton_csv(PlantObject *o, PyObject *unused) {
    if (need_skeleton(o)) return NULL;
    Diag d;
    if (diag_open(&d)) return NULL;
    int st;
    Py_BEGIN_ALLOW_THREADS
    st = syl_skeleton_write_csv(o->pl.skeleton, d.f);
    Py_END_ALLOW_THREADS
    if (st) return raise_status(st, &d);
    return diag_text(&d);
}

/* An (H, W, 4) RGBA picture by the Embree renderer; with transparent, no ground and the
 * alpha is the plant's coverage, else 255. */
static PyObject *plant_render(PlantObject *o, PyObject *args, PyObject *kw) {
    static char *kwl[] = {"width", "height", "view", "samples", "threads", "transparent", NULL};
    int w = 512, h = 512, view = SYL_VIEW_AUTO, samples = 0, threads = 0, transparent = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|iiiiip", kwl, &w, &h, &view, &samples, &threads, &transparent))
        return NULL;
    if (need_mesh(o)) return NULL;
    if (w < 1 || h < 1 || w > 16384 || h > 16384)
        return PyErr_Format(PyExc_ValueError, "a picture is 1 to 16384 pixels a side, not %d x %d", w, h);
    if (view < SYL_VIEW_ISO || view > SYL_VIEW_AUTO) return PyErr_Format(PyExc_ValueError, "no view %d", view);
    size_t px = (size_t)w * (size_t)h;
    uint8_t *rgb = malloc(px * 3), *alpha = malloc(px), *rgba = malloc(px * 4);
    Diag d;
    if (!rgb || !alpha || !rgba || diag_open(&d)) {
        free(rgb);
        free(alpha);
        free(rgba);
        return PyErr_Occurred() ? NULL : PyErr_NoMemory();
    }
    SylRenderOptions ro = {.width = w, .height = h, .view = (SylView)view, .samples = samples, .threads = threads,
                           .diag = d.f, .alpha = alpha, .ground = transparent ? -1 : 0};
    int st;
    Py_BEGIN_ALLOW_THREADS
    st = syl_render_draw_mesh(o->pl.mesh, &ro, rgb);
    if (!st)
        for (size_t i = 0; i < px; i++) {
            memcpy(rgba + 4 * i, rgb + 3 * i, 3);
            rgba[4 * i + 3] = transparent ? alpha[i] : 255;
        }
    Py_END_ALLOW_THREADS
    free(rgb);
    free(alpha);
    if (st) {
        free(rgba);
        return raise_status(st, &d);
    }
    diag_drop(&d);
    BufferObject *b = (BufferObject *)buffer_new(NULL, rgba, "B", 1, h, (Py_ssize_t)w * 4);
    if (!b) return NULL;
    b->ndim = 3; /* (H, W, 4) */
    b->shape[1] = w;
    b->shape[2] = 4;
    b->strides[0] = (Py_ssize_t)w * 4;
    b->strides[1] = 4;
    b->strides[2] = 1;
    return (PyObject *)b;
}

/* Every metric of `sylva compare`, by key (per-order ones as key_i). */
static PyObject *plant_metrics(PlantObject *o, PyObject *args, PyObject *kw) {
    static char *kwl[] = {"threads", NULL};
    int threads = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|i", kwl, &threads)) return NULL;
    if (need_skeleton(o)) return NULL;
    Diag d;
    if (diag_open(&d)) return NULL;
    SylMetrics m;
    SylMetricsOptions mo = {.mesh = o->pl.mesh, .threads = threads, .diag = d.f};
    int st;
    Py_BEGIN_ALLOW_THREADS
    st = syl_metrics_compute(o->pl.skeleton, &mo, &m);
    Py_END_ALLOW_THREADS
    if (st) return raise_status(st, &d);
    diag_drop(&d);
    PyObject *out = PyDict_New();
    for (int i = 0; out && i < syl_metrics_count; i++) {
        const SylMetricInfo *mi = &syl_metrics_info[i];
        int orders = mi->per_order ? (int)m.strahler - 1 : 1;
        for (int k = 1; out && k <= orders; k++) {
            char key[96];
            if (mi->per_order) snprintf(key, sizeof key, "%s_%d", mi->key, k);
            else snprintf(key, sizeof key, "%s", mi->key);
            PyObject *v = PyFloat_FromDouble(syl_metrics_value(&m, i, k));
            if (!v || PyDict_SetItemString(out, key, v)) Py_CLEAR(out);
            Py_XDECREF(v);
        }
    }
    return out;
}

static PyMethodDef plant_methods[] = {
    {"info", (PyCFunction)plant_info, METH_NOARGS, "counts and timings"},
    {"nodes", (PyCFunction)plant_nodes, METH_NOARGS, "the skeleton's nodes, raw records"},
    {"organs", (PyCFunction)plant_organs, METH_NOARGS, "the skeleton's organs, raw records"},
    {"mesh_arrays", (PyCFunction)plant_mesh_arrays, METH_NOARGS, "positions, normals, uvs, triangles, groups"},
    {"levels", (PyCFunction)plant_levels, METH_NOARGS, "the levels of detail (lod=), LOD0 first"},
    {"impostor", (PyCFunction)plant_impostor, METH_NOARGS, "the impostor's atlases (impostor=), or None"},
    {"wind", (PyCFunction)plant_wind, METH_NOARGS, "the wind's joints and keys (wind=), or None"},
    {"leaf_sets", (PyCFunction)(void (*)(void))plant_leaf_sets, METH_VARARGS | METH_KEYWORDS,
     "leaf_sets(cards=False, level=0): the leaves as instance sets, each with its prototype"},
    {"skin", (PyCFunction)plant_skin, METH_VARARGS, "skin(level=0): each vertex's joints and weights, or None"},
    {"write", (PyCFunction)plant_write, METH_VARARGS, "write(path): .glb, .obj or .ply by the extension"},
    {"skeleton_csv", (PyCFunction)plant_skeleton_csv, METH_NOARGS, "the skeleton as `sylva skeleton` writes it"},
    {"render", (PyCFunction)(void (*)(void))plant_render, METH_VARARGS | METH_KEYWORDS, "an RGBA picture"},
    {"metrics", (PyCFunction)(void (*)(void))plant_metrics, METH_VARARGS | METH_KEYWORDS, "compare's figures"},
    {NULL, NULL, 0, NULL},
};

static PyTypeObject PlantType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "sylva._core.Plant",
    .tp_basicsize = sizeof(PlantObject),
    .tp_dealloc = (destructor)plant_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_methods = plant_methods,
    .tp_doc = "a built plant: skeleton and mesh",
};

/* ---- Ecosystem: a run's years, snapshots and terrain ---- */

typedef struct {
    PyObject_HEAD
    SylEcoYear *years;
    size_t nyears, years_cap;
    PyObject *snapshots; /* {year: Buffer of SylEcoPlant records} */
    SylTerrain *terrain;
    SylEcoModel *model;
    SylEcoStats stats;
    int interrupted;
} EcoObject;

static void eco_dealloc(EcoObject *o) {
    free(o->years);
    Py_XDECREF(o->snapshots);
    syl_terrain_free(o->terrain);
    free(o->model);
    Py_TYPE(o)->tp_free((PyObject *)o);
}

static void eco_on_year(void *user, const SylEcoYear *y) {
    EcoObject *o = user;
    if (o->nyears == o->years_cap) {
        size_t cap = o->years_cap ? 2 * o->years_cap : 64;
        SylEcoYear *n = realloc(o->years, cap * sizeof *n);
        if (!n) return; /* the year is left out; the run's own limits catch a real shortage */
        o->years = n, o->years_cap = cap;
    }
    o->years[o->nyears++] = *y;
}

static int eco_on_snapshot(void *user, int year, const SylEcoPlant *plants, size_t n) {
    EcoObject *o = user;
    PyGILState_STATE g = PyGILState_Ensure();
    int stop = 0;
    SylEcoPlant *copy = malloc(n ? n * sizeof *copy : 1);
    PyObject *key = PyLong_FromLong(year), *buf = NULL;
    if (copy) {
        if (n) memcpy(copy, plants, n * sizeof *copy);
        buf = buffer_new(NULL, copy, "B", 1, (Py_ssize_t)n, (Py_ssize_t)sizeof *copy);
    }
    if (!key || !buf || PyDict_SetItem(o->snapshots, key, buf)) stop = 1;
    if (PyErr_CheckSignals()) stop = 1, o->interrupted = 1;
    if (stop && !o->interrupted) PyErr_Clear();
    Py_XDECREF(key);
    Py_XDECREF(buf);
    PyGILState_Release(g);
    return stop ? SYL_ELIMIT : 0;
}

/* Ctrl-C is looked at once a year, and the run stops at the year's end through the
 * checkpoint hook (every year), the only place a simulation can be stopped from outside. */
static int eco_on_checkpoint(void *user, int year, const SylEcoPlant *plants, size_t n) {
    EcoObject *o = user;
    PyGILState_STATE g = PyGILState_Ensure();
    if (PyErr_CheckSignals()) o->interrupted = 1;
    PyGILState_Release(g);
    return o->interrupted ? SYL_ELIMIT : 0;
}

static PyTypeObject EcoType;

static PyObject *program_ecosystem(ProgramObject *o, PyObject *args, PyObject *kw) {
    static char *kwl[] = {"years", "seed", "threads", "max_plants", "tiles_x", "tiles_z", "snapshots", NULL};
    int years = 0, threads = 0, tx = 0, tz = 0;
    PyObject *seedo = Py_None, *snaps = Py_None;
    unsigned long long max_plants = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|iOiKiiO", kwl, &years, &seedo, &threads, &max_plants, &tx, &tz,
                                     &snaps))
        return NULL;
    int snap[SYL_ECO_MAX_SNAPSHOTS], nsnap = 0;
    if (snaps != Py_None) {
        PyObject *seq = PySequence_Fast(snaps, "snapshots is a sequence of years");
        if (!seq) return NULL;
        Py_ssize_t k = PySequence_Fast_GET_SIZE(seq);
        if (k > SYL_ECO_MAX_SNAPSHOTS) {
            Py_DECREF(seq);
            return PyErr_Format(PyExc_ValueError, "at most %d snapshots", SYL_ECO_MAX_SNAPSHOTS);
        }
        for (Py_ssize_t i = 0; i < k; i++) {
            long y = PyLong_AsLong(PySequence_Fast_GET_ITEM(seq, i));
            if (y == -1 && PyErr_Occurred()) {
                Py_DECREF(seq);
                return NULL;
            }
            snap[nsnap++] = (int)y;
        }
        Py_DECREF(seq);
    }
    EcoObject *e = PyObject_New(EcoObject, &EcoType);
    if (!e) return NULL;
    e->years = NULL, e->nyears = e->years_cap = 0, e->terrain = NULL, e->interrupted = 0;
    memset(&e->stats, 0, sizeof e->stats);
    e->model = calloc(1, sizeof *e->model);
    e->snapshots = PyDict_New();
    Diag d;
    if (!e->model || !e->snapshots || diag_open(&d)) {
        Py_DECREF(e);
        return PyErr_Occurred() ? NULL : PyErr_NoMemory();
    }
    SylEcoOptions eo = {.years = years, .threads = threads, .max_plants = max_plants, .tiles_x = tx, .tiles_z = tz,
                        .on_year = eco_on_year, .on_snapshot = eco_on_snapshot, .on_checkpoint = eco_on_checkpoint,
                        .every = 1, .user = e, .diag = d.f};
    if (snaps != Py_None) eo.snapshots = snap, eo.nsnapshots = nsnap;
    if (seedo != Py_None) {
        eo.use_seed = 1;
        eo.seed = PyLong_AsUnsignedLongLongMask(seedo);
        if (PyErr_Occurred()) {
            diag_drop(&d);
            Py_DECREF(e);
            return NULL;
        }
    }
    int st;
    Py_BEGIN_ALLOW_THREADS
    st = syl_ecosystem_run(o->p, &eo, e->model, &e->terrain, &e->stats);
    Py_END_ALLOW_THREADS
    if (e->interrupted || PyErr_Occurred()) {
        diag_drop(&d);
        Py_DECREF(e);
        if (!PyErr_Occurred()) PyErr_SetNone(PyExc_KeyboardInterrupt);
        return NULL;
    }
    if (st) {
        Py_DECREF(e);
        return raise_status(st, &d);
    }
    diag_drop(&d);
    return (PyObject *)e;
}

static PyObject *eco_info(EcoObject *o, PyObject *unused) {
    PyObject *names = PyList_New(o->model->nspecies);
    for (int i = 0; names && i < o->model->nspecies; i++) {
        PyObject *n = PyUnicode_FromString(o->model->species[i].name);
        if (!n) Py_CLEAR(names);
        else PyList_SET_ITEM(names, i, n);
    }
    if (!names) return NULL;
    const SylTerrain *t = o->terrain;
    return Py_BuildValue("{s:N,s:i,s:K,s:n,s:d,s:d,s:i,s:i,s:d,s:d,s:d}", "species", names, "years", o->model->years,
                         "plant_years", (unsigned long long)o->stats.plant_years, "peak_plants",
                         (Py_ssize_t)o->stats.peak_plants, "seconds", o->stats.seconds, "cpu_seconds",
                         o->stats.cpu_seconds, "nx", t ? t->nx : 0, "nz", t ? t->nz : 0, "cell", t ? t->cell : 0.0,
                         "x0", t ? t->x0 : 0.0, "z0", t ? t->z0 : 0.0);
}

static PyObject *eco_years(EcoObject *o, PyObject *unused) {
    return buffer_new((PyObject *)o, o->years, "B", 1, (Py_ssize_t)o->nyears, (Py_ssize_t)sizeof(SylEcoYear));
}

static PyObject *eco_snapshots(EcoObject *o, PyObject *unused) { return PyDict_Copy(o->snapshots); }

/* {name: (nz, nx) float32 view} of the terrain's computed factors */
static PyObject *eco_terrain(EcoObject *o, PyObject *unused) {
    PyObject *d = PyDict_New();
    const SylTerrain *t = o->terrain;
    for (int f = 0; d && t && f < SYL_TERRAIN_FACTORS; f++) {
        float *a = f == SYL_TERRAIN_ALTITUDE ? t->height : t->factor[f];
        if (!a) continue;
        PyObject *b = buffer_new((PyObject *)o, a, "f", 4, t->nz, t->nx);
        if (!b || PyDict_SetItemString(d, syl_terrain_factor_name((SylTerrainFactor)f), b)) Py_CLEAR(d);
        Py_XDECREF(b);
    }
    return d;
}

static PyMethodDef eco_methods[] = {
    {"info", (PyCFunction)eco_info, METH_NOARGS, "species, terrain size, statistics"},
    {"years", (PyCFunction)eco_years, METH_NOARGS, "every year's record, raw"},
    {"snapshots", (PyCFunction)eco_snapshots, METH_NOARGS, "{year: plant records, raw}"},
    {"terrain", (PyCFunction)eco_terrain, METH_NOARGS, "{factor: 2-D float32 view}"},
    {NULL, NULL, 0, NULL},
};

static PyTypeObject EcoType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "sylva._core.Ecosystem",
    .tp_basicsize = sizeof(EcoObject),
    .tp_dealloc = (destructor)eco_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_methods = eco_methods,
    .tp_doc = "an ecosystem run",
};

static PyMethodDef program_methods[] = {
    {"info", (PyCFunction)program_info, METH_NOARGS, "name, kind, steps, seed, symbols, path"},
    {"setting", (PyCFunction)program_setting, METH_VARARGS, "setting(name) -> float"},
    {"externs", (PyCFunction)program_externs, METH_NOARGS, "[(name, nparams, has_default)] of its externs"},
    {"bind", (PyCFunction)program_bind, METH_VARARGS, "bind(name, fn or None) to an extern"},
    {"describe", (PyCFunction)program_describe, METH_NOARGS, "every model's parameters as JSON (or None)"},
    {"derive", (PyCFunction)(void (*)(void))program_derive, METH_VARARGS | METH_KEYWORDS, "derive the string"},
    {"build", (PyCFunction)(void (*)(void))program_build, METH_VARARGS | METH_KEYWORDS, "build skeleton and mesh"},
    {"ecosystem", (PyCFunction)(void (*)(void))program_ecosystem, METH_VARARGS | METH_KEYWORDS, "run an ecosystem"},
    {NULL, NULL, 0, NULL},
};

static PyTypeObject ProgramType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "sylva._core.Program",
    .tp_basicsize = sizeof(ProgramObject),
    .tp_dealloc = (destructor)program_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_methods = program_methods,
    .tp_doc = "a compiled model",
};

static PyObject *core_set_errors(PyObject *self, PyObject *args) {
    PyObject *c, *l;
    if (!PyArg_ParseTuple(args, "OO", &c, &l)) return NULL;
    Py_XSETREF(CompileError, Py_NewRef(c));
    Py_XSETREF(LimitError, Py_NewRef(l));
    Py_RETURN_NONE;
}

/* Byte offsets of the record fields, for numpy's structured dtypes (sylva/_layout.py). */
static PyObject *wind_layouts(void) {
#define F(T, f) #f, (Py_ssize_t)offsetof(T, f)
    return Py_BuildValue("{s:{s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n},s:{s:n,s:n,s:n,s:n,s:n,s:n,s:n}}",
                         "wind_stem", F(SylWindStem, joint), F(SylWindStem, parent), F(SylWindStem, base),
                         F(SylWindStem, dir), F(SylWindStem, length), F(SylWindStem, radius),
                         F(SylWindStem, parent_radius), F(SylWindStem, phase), F(SylWindStem, stiffness),
                         F(SylWindStem, order), "itemsize", (Py_ssize_t)sizeof(SylWindStem), "wind_joint",
                         F(SylWindJoint, stem), F(SylWindJoint, parent), F(SylWindJoint, amplitude),
                         F(SylWindJoint, frequency), F(SylWindJoint, blend_start), F(SylWindJoint, blend_length),
                         "itemsize", (Py_ssize_t)sizeof(SylWindJoint));
#undef F
}

static PyObject *layouts(void) {
#define F(T, f) #f, (Py_ssize_t)offsetof(T, f)
    return Py_BuildValue("{s:{s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n},"
                         "s:{s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n},"
                         "s:{s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n,s:n},s:{s:n,s:n,s:n,s:n,s:n},s:i}",
                         "node", F(SylNode, pos), F(SylNode, h), F(SylNode, l), F(SylNode, u), F(SylNode, radius),
                         F(SylNode, parent), F(SylNode, axis), F(SylNode, order), F(SylNode, kind),
                         F(SylNode, material), F(SylNode, flags), F(SylNode, module), "itemsize",
                         (Py_ssize_t)sizeof(SylNode), "organ", F(SylOrgan, pos), F(SylOrgan, h), F(SylOrgan, l),
                         F(SylOrgan, u), F(SylOrgan, size), F(SylOrgan, node), F(SylOrgan, kind),
                         F(SylOrgan, material), F(SylOrgan, module), "itemsize", (Py_ssize_t)sizeof(SylOrgan),
                         "eco_plant", F(SylEcoPlant, id), F(SylEcoPlant, x), F(SylEcoPlant, z),
                         F(SylEcoPlant, height), F(SylEcoPlant, vigour), F(SylEcoPlant, age), F(SylEcoPlant, species),
                         F(SylEcoPlant, state), "itemsize", (Py_ssize_t)sizeof(SylEcoPlant), "eco_year",
                         F(SylEcoYear, year), F(SylEcoYear, count), F(SylEcoYear, cover), F(SylEcoYear, mean_height),
                         "itemsize", (Py_ssize_t)sizeof(SylEcoYear), "eco_max_species", SYL_ECO_MAX_SPECIES);
#undef F
}

static PyMethodDef core_methods[] = {
    {"compile", (PyCFunction)(void (*)(void))core_compile, METH_VARARGS | METH_KEYWORDS,
     "compile(path, text=None, model=None, overrides=None, lint=False, validate=True) -> (Program, warnings)"},
    {"models", core_models, METH_VARARGS, "models(path, text=None) -> names"},
    {"png_rgba", core_png_rgba, METH_VARARGS, "png_rgba(bytes, width, height) -> PNG bytes"},
    {"instance_quads", core_instance_quads, METH_VARARGS,
     "instance_quads(t, r, s) -> (4n, 3) float32: a square per instance, centred on it, along R x and R y"},
    {"mesh_edges", core_mesh_edges, METH_VARARGS,
     "mesh_edges(triangles, nverts) -> (edges, loop_edge): each side once and every loop's edge"},
    {"_set_errors", core_set_errors, METH_VARARGS, "the package's CompileError and LimitError"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef core_module = {PyModuleDef_HEAD_INIT, "sylva._core", "libsylva's binding", -1,
                                         core_methods, NULL, NULL, NULL, NULL};

PyMODINIT_FUNC PyInit__core(void) {
    PyTypeObject *types[] = {&BufferType, &ProgramType, &StringType, &PlantType, &EcoType};
    for (size_t i = 0; i < sizeof types / sizeof *types; i++)
        if (PyType_Ready(types[i])) return NULL;
    PyObject *m = PyModule_Create(&core_module);
    if (!m) return NULL;
    PyObject *lay = layouts(), *wl = lay ? wind_layouts() : NULL;
    if (wl && PyDict_Update(lay, wl)) Py_CLEAR(lay);
    Py_XDECREF(wl);
    if (!lay || PyModule_AddObject(m, "LAYOUT", lay) || PyModule_AddStringConstant(m, "VERSION", SYLVA_VERSION) ||
        PyModule_AddIntConstant(m, "HAVE_DESCRIBE",
#ifdef HAVE_DESCRIBE
                                1
#else
                                0
#endif
                                )) {
        Py_XDECREF(lay);
        Py_DECREF(m);
        return NULL;
    }
    const char *kinds[SYL_KIND_COUNT];
    for (int i = 0; i < SYL_KIND_COUNT; i++) kinds[i] = syl_kind_names[i];
    PyObject *kl = PyList_New(SYL_KIND_COUNT);
    for (int i = 0; kl && i < SYL_KIND_COUNT; i++) PyList_SET_ITEM(kl, i, PyUnicode_FromString(kinds[i]));
    if (!kl || PyModule_AddObject(m, "ORGAN_KINDS", kl)) {
        Py_XDECREF(kl);
        Py_DECREF(m);
        return NULL;
    }
    return m;
}
