/* SylEcoExchange over MPI ranks (built with MPI=1; docs/distributed.md). Each rank runs a
 * contiguous run of tiles (balance.c). A post to a tile of the same rank is kept as a pointer,
 * as in exchange.c; the barrier packs the posts to other ranks' tiles into one message per
 * rank (records: channel, from, to, count, then the plants as bytes of SylEcoPlant), trades
 * the sizes with MPI_Alltoall and the messages with MPI_Isend/MPI_Irecv/MPI_Waitall, and
 * points the receiver's mailboxes into what arrived. Counts, gathers and checkpoints go
 * through collectives, so every rank sees the same totals in the same order. */
#include <limits.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "eco/eco.h"
#include "eco/mpi_lazy.h"
#include "util/diag.h"

LAZY_LIB_GETTER(MpiApi, mpi_api, "libmpi.so.40", "an ecosystem over MPI ranks", true, MPI_FUNCS)
void *mpi_global(const char *name) {
    mpi_api();
    return lazy_lib_sym(&mpi_api_lib, name);
}

typedef struct Box {
    const SylEcoPlant *p;
    size_t n;
    int got; /* arrived from another rank: points into recv */
} Box;

typedef struct Record { /* 32 bytes: the plants after it stay 8-aligned */
    int32_t channel, from, to, pad;
    uint64_t n, pad2;
} Record;

enum { CHANNELS = 3 };

struct SylEcoMpi {
    int rank, size;
    MPI_Comm comm;
    MPI_Datatype plant;
    SylSink sink;           /* where a failure that ends the job is said (copied; report NULL: nowhere) */
    SylEcoExchange ops;
    int ntiles, every, pending;
    int *owner, *next;
    Box *box;              /* [channel][to][from] */
    uint8_t **send, **recv; /* per rank */
    uint64_t *send_len, *recv_len;
    MPI_Request *req;
    uint64_t plants_sent, bytes_sent, halo_received, plants_moved, barriers;
    /* the watchdog: a rank that waits on the others longer than timeout seconds ends the job */
    double timeout;         /* SYLVA_RANK_TIMEOUT; 0: none */
    _Atomic int64_t since;  /* ms (CLOCK_MONOTONIC) when this rank began to wait; 0: it is not */
    _Atomic int quit;
    pthread_t watch;
    int watching;
    int *pid, *host;        /* each rank's pid, and a hash of its host's name */
};

static Box *box_of(SylEcoMpi *m, int channel, int to, int from) {
    return &m->box[((size_t)channel * m->ntiles + (size_t)to) * m->ntiles + (size_t)from];
}

static void fail(SylEcoMpi *m, const char *what) {
    sink_error(&m->sink, "rank %d of %d: %s; aborting the job", m->rank, m->size, what);
    MPI_Abort(m->comm, SYL_EIO);
}

/* Any MPI error (a rank gone, a message lost) ends the whole job with a message, not a hang:
 * the communicator returns errors (MPI_ERRORS_RETURN) and every call is checked here, so that
 * the message goes to the caller's sink. */
static void check(SylEcoMpi *m, int code) {
    if (code == MPI_SUCCESS) return;
    char text[MPI_MAX_ERROR_STRING], what[MPI_MAX_ERROR_STRING + 8];
    int len = 0;
    MPI_Error_string(code, text, &len);
    snprintf(what, sizeof what, "MPI: %s", text);
    fail(m, what);
}

static int64_t now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

static void wait_begin(SylEcoMpi *m) { atomic_store(&m->since, now_ms()); }
static void wait_end(SylEcoMpi *m) { atomic_store(&m->since, 0); }

/* The ranks of this host that are stopped (SIGSTOP, a debugger), from /proc: "rank 1 (pid
 * 123) is stopped" into buf, or "" when none is, or they are on other hosts. */
static void stopped_ranks(const SylEcoMpi *m, char *buf, size_t n) {
    size_t at = 0;
    buf[0] = 0;
    for (int r = 0; r < m->size && at + 80 < n; r++) {
        if (r == m->rank || m->host[r] != m->host[m->rank]) continue;
        char path[64], line[512];
        snprintf(path, sizeof path, "/proc/%d/stat", m->pid[r]);
        FILE *f = fopen(path, "re");
        if (!f) continue;
        char *got = fgets(line, sizeof line, f);
        fclose(f);
        const char *paren = got ? strrchr(line, ')') : NULL; /* "pid (name) S ..." */
        if (paren && (paren[2] == 'T' || paren[2] == 't'))
            at += (size_t)snprintf(buf + at, n - at, "%srank %d (pid %d) is stopped", at ? ", " : "; ", r, m->pid[r]);
    }
}

/* A rank that stops answering (stopped, hung, its host gone) would leave the others waiting in
 * MPI for ever: past the timeout this rank says so and exits, and the launcher ends the job
 * (as when a rank is killed). The main thread may be inside MPI: this thread makes no MPI
 * call, and leaves by _exit. */
static void *watchdog(void *arg) {
    SylEcoMpi *m = arg;
    const struct timespec tick = {0, 200 * 1000000};
    while (!atomic_load(&m->quit)) {
        nanosleep(&tick, NULL);
        int64_t since = atomic_load(&m->since);
        if (!since || now_ms() - since < (int64_t)(m->timeout * 1000)) continue;
        char who[1024];
        stopped_ranks(m, who, sizeof who);
        /* from the watchdog's thread */
        sink_error(&m->sink,
                   "rank %d of %d: no answer from the other ranks for %g s%s; ending the job "
                   "(SYLVA_RANK_TIMEOUT sets the time)",
                   m->rank, m->size, m->timeout, who);
        _exit(SYL_EIO);
    }
    return NULL;
}

static void mpi_post(void *ctx, int channel, int from, int to, const SylEcoPlant *p, size_t n) {
    Box *b = box_of(ctx, channel, to, from);
    b->p = p;
    b->n = n;
    b->got = 0;
}

static const SylEcoPlant *mpi_take(void *ctx, int channel, int to, int from, size_t *n) {
    Box *b = box_of(ctx, channel, to, from);
    *n = b->n;
    return b->p;
}

static int dest_of(const SylEcoMpi *m, int channel, int to) {
    return channel == SYL_ECO_MOVE ? m->next[to] : m->owner[to];
}

static void mpi_barrier(void *ctx) {
    SylEcoMpi *m = ctx;
    size_t nbox = (size_t)CHANNELS * m->ntiles * m->ntiles;
    for (size_t i = 0; i < nbox; i++)
        if (m->box[i].got) m->box[i] = (Box){0}; /* the last barrier's arrivals */
    for (int r = 0; r < m->size; r++) {
        free(m->recv[r]), free(m->send[r]);
        m->recv[r] = m->send[r] = NULL;
        m->send_len[r] = 0;
    }
    /* what goes to each rank: its size, then the records */
    for (int pass = 0; pass < 2; pass++) {
        for (int r = 0; pass && r < m->size; r++) {
            if (m->send_len[r] && !(m->send[r] = malloc(m->send_len[r]))) fail(m, "out of memory for a message");
            m->send_len[r] = 0;
        }
        for (int ch = 0; ch < CHANNELS; ch++)
            for (int to = 0; to < m->ntiles; to++)
                for (int from = 0; from < m->ntiles; from++) {
                    Box *b = box_of(m, ch, to, from);
                    int r = dest_of(m, ch, to);
                    if (!b->n || r == m->rank) continue;
                    size_t len = sizeof(Record) + b->n * sizeof(SylEcoPlant);
                    if (pass) {
                        Record h = {.channel = ch, .from = from, .to = to, .n = b->n};
                        memcpy(m->send[r] + m->send_len[r], &h, sizeof h);
                        memcpy(m->send[r] + m->send_len[r] + sizeof h, b->p, b->n * sizeof(SylEcoPlant));
                        m->plants_sent += b->n;
                        *b = (Box){0};
                    }
                    m->send_len[r] += len;
                }
    }
    wait_begin(m);
    check(m, MPI_Alltoall(m->send_len, 1, MPI_UINT64_T, m->recv_len, 1, MPI_UINT64_T, m->comm));
    int nreq = 0;
    for (int r = 0; r < m->size; r++) {
        if (m->recv_len[r] > INT_MAX || m->send_len[r] > INT_MAX) fail(m, "a message over 2 GB (use more tiles or ranks)");
        if (m->recv_len[r]) {
            if (!(m->recv[r] = malloc(m->recv_len[r]))) fail(m, "out of memory for a message");
            check(m, MPI_Irecv(m->recv[r], (int)m->recv_len[r], MPI_BYTE, r, 0, m->comm, &m->req[nreq++]));
        }
    }
    for (int r = 0; r < m->size; r++)
        if (m->send_len[r]) {
            check(m, MPI_Isend(m->send[r], (int)m->send_len[r], MPI_BYTE, r, 0, m->comm, &m->req[nreq++]));
            m->bytes_sent += m->send_len[r];
        }
    check(m, MPI_Waitall(nreq, m->req, MPI_STATUSES_IGNORE));
    wait_end(m);
    for (int r = 0; r < m->size; r++)
        for (uint64_t at = 0; at < m->recv_len[r];) {
            Record h;
            memcpy(&h, m->recv[r] + at, sizeof h);
            if (h.channel < 0 || h.channel >= CHANNELS || h.from < 0 || h.from >= m->ntiles || h.to < 0 ||
                h.to >= m->ntiles || h.n > (m->recv_len[r] - at - sizeof h) / sizeof(SylEcoPlant))
                fail(m, "a malformed message");
            Box *b = box_of(m, h.channel, h.to, h.from);
            b->p = (const SylEcoPlant *)(m->recv[r] + at + sizeof h);
            b->n = h.n;
            b->got = 1;
            if (h.channel == SYL_ECO_HALO) m->halo_received += h.n;
            if (h.channel == SYL_ECO_MOVE) m->plants_moved += h.n;
            at += sizeof h + h.n * sizeof(SylEcoPlant);
        }
    if (m->pending) { /* the new owners; what was posted under the old ones is stale */
        memcpy(m->owner, m->next, (size_t)m->ntiles * sizeof *m->owner);
        m->pending = 0;
        for (size_t i = 0; i < nbox; i++)
            if (!m->box[i].got) m->box[i] = (Box){0};
    }
    m->barriers++;
}

static int mpi_owns(void *ctx, int tile) {
    SylEcoMpi *m = ctx;
    return m->owner[tile] == m->rank;
}

static void mpi_sum(void *ctx, int64_t *v, size_t n) {
    SylEcoMpi *m = ctx;
    if (n > INT_MAX) fail(m, "too many sums");
    wait_begin(m);
    check(m, MPI_Allreduce(MPI_IN_PLACE, v, (int)n, MPI_INT64_T, MPI_SUM, m->comm));
    wait_end(m);
}

static int mpi_gather(void *ctx, const SylEcoPlant *p, size_t n, SylEcoPlant **all, size_t *nall) {
    SylEcoMpi *m = ctx;
    *all = NULL;
    *nall = 0;
    if (n > INT_MAX) fail(m, "over 2^31 plants on one rank");
    int mine = (int)n, *counts = NULL, *displs = NULL;
    if (m->rank == 0) {
        counts = malloc((size_t)m->size * sizeof *counts);
        displs = malloc((size_t)m->size * sizeof *displs);
        if (!counts || !displs) fail(m, "out of memory for a gather");
    }
    wait_begin(m);
    check(m, MPI_Gather(&mine, 1, MPI_INT, counts, 1, MPI_INT, 0, m->comm));
    wait_end(m);
    int64_t total = 0;
    for (int r = 0; m->rank == 0 && r < m->size; r++) {
        if (total + counts[r] > INT_MAX) fail(m, "over 2^31 plants to gather");
        displs[r] = (int)total;
        total += counts[r];
    }
    if (m->rank == 0 && !(*all = malloc((size_t)(total ? total : 1) * sizeof **all))) fail(m, "out of memory for a gather");
    wait_begin(m);
    check(m, MPI_Gatherv(p, mine, m->plant, *all, counts, displs, m->plant, 0, m->comm));
    wait_end(m);
    *nall = (size_t)total;
    free(counts), free(displs);
    return 0;
}

static int mpi_rebalance(void *ctx, int year, const int64_t *plants, int ntiles) {
    SylEcoMpi *m = ctx;
    if (m->every <= 0 || year % m->every || ntiles != m->ntiles) return 0;
    eco_balance_cut(plants, ntiles, m->size, m->next);
    m->pending = memcmp(m->next, m->owner, (size_t)ntiles * sizeof *m->owner) != 0;
    return m->pending;
}

SylEcoMpi *syl_ecosystem_mpi_start(int *argc, char ***argv, const SylSink *sink) {
    /* only under a launcher: a plain run stays one plain process */
    if (!getenv("OMPI_COMM_WORLD_SIZE") && !getenv("PMIX_RANK") && !getenv("PMI_RANK")) return NULL;
    SylEcoMpi *m = calloc(1, sizeof *m);
    if (!m) return NULL;
    int provided;
    MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided); /* MPI from the main thread only */
    m->comm = MPI_COMM_WORLD;
    if (sink) m->sink = *sink;
    check(m, MPI_Comm_rank(m->comm, &m->rank));
    check(m, MPI_Comm_size(m->comm, &m->size));
    MPI_Comm_set_errhandler(m->comm, MPI_ERRORS_RETURN);
    check(m, MPI_Type_contiguous((int)sizeof(SylEcoPlant), MPI_BYTE, &m->plant));
    check(m, MPI_Type_commit(&m->plant));
    const char *t = getenv("SYLVA_RANK_TIMEOUT");
    m->timeout = t ? atof(t) : 600;
    m->pid = calloc((size_t)m->size, sizeof *m->pid);
    m->host = calloc((size_t)m->size, sizeof *m->host);
    if (!m->pid || !m->host) fail(m, "out of memory");
    char name[256] = "";
    gethostname(name, sizeof name - 1);
    unsigned h = 2166136261u; /* FNV-1a */
    for (const char *c = name; *c; c++) h = (h ^ (unsigned char)*c) * 16777619u;
    int mine[2] = {(int)getpid(), (int)h}, *all = malloc(2 * (size_t)m->size * sizeof *all);
    if (!all) fail(m, "out of memory");
    check(m, MPI_Allgather(mine, 2, MPI_INT, all, 2, MPI_INT, m->comm));
    for (int r = 0; r < m->size; r++) m->pid[r] = all[2 * r], m->host[r] = all[2 * r + 1];
    free(all);
    if (m->timeout > 0) m->watching = !pthread_create(&m->watch, NULL, watchdog, m);
    return m;
}

int syl_ecosystem_mpi_rank(const SylEcoMpi *m) { return m ? m->rank : 0; }
int syl_ecosystem_mpi_size(const SylEcoMpi *m) { return m ? m->size : 1; }

const SylEcoExchange *syl_ecosystem_mpi_exchange(SylEcoMpi *m, int ntiles, int rebalance) {
    if (!m || ntiles < 1) return NULL;
    m->ntiles = ntiles;
    m->every = rebalance;
    m->owner = malloc((size_t)ntiles * sizeof *m->owner);
    m->next = malloc((size_t)ntiles * sizeof *m->next);
    m->box = calloc((size_t)CHANNELS * ntiles * ntiles, sizeof *m->box);
    m->send = calloc((size_t)m->size, sizeof *m->send);
    m->recv = calloc((size_t)m->size, sizeof *m->recv);
    m->send_len = calloc((size_t)m->size, sizeof *m->send_len);
    m->recv_len = calloc((size_t)m->size, sizeof *m->recv_len);
    m->req = calloc((size_t)2 * m->size, sizeof *m->req);
    if (!m->owner || !m->next || !m->box || !m->send || !m->recv || !m->send_len || !m->recv_len || !m->req)
        fail(m, "out of memory for the tiles");
    eco_balance_cut(NULL, ntiles, m->size, m->owner);
    memcpy(m->next, m->owner, (size_t)ntiles * sizeof *m->owner);
    m->ops = (SylEcoExchange){.post = mpi_post, .barrier = mpi_barrier, .take = mpi_take, .owns = mpi_owns,
                              .sum = mpi_sum, .gather = mpi_gather, .rebalance = mpi_rebalance, .ctx = m};
    return &m->ops;
}

void syl_ecosystem_mpi_traffic(const SylEcoMpi *m, uint64_t *plants_sent, uint64_t *bytes_sent, uint64_t *halo_received,
                         uint64_t *plants_moved, uint64_t *barriers) {
    *plants_sent = m ? m->plants_sent : 0;
    *plants_moved = m ? m->plants_moved : 0;
    *bytes_sent = m ? m->bytes_sent : 0;
    *halo_received = m ? m->halo_received : 0;
    *barriers = m ? m->barriers : 0;
}

void eco_mpi_sum(SylEcoMpi *m, int64_t *v, size_t n) {
    if (m) mpi_sum(m, v, n);
}

int eco_mpi_gather(SylEcoMpi *m, const void *mine, size_t n, uint8_t **all, size_t *lens) {
    *all = NULL;
    if (!m) { /* one process: a copy */
        lens[0] = n;
        if (!(*all = malloc(n ? n : 1))) return SYL_ELIMIT;
        memcpy(*all, mine, n);
        return SYL_OK;
    }
    if (n > INT_MAX) fail(m, "over 2 GB to gather from one rank");
    int len = (int)n, *counts = NULL, *displs = NULL;
    if (m->rank == 0 && (!(counts = malloc((size_t)m->size * sizeof *counts)) ||
                         !(displs = malloc((size_t)m->size * sizeof *displs))))
        fail(m, "out of memory for a gather");
    wait_begin(m);
    check(m, MPI_Gather(&len, 1, MPI_INT, counts, 1, MPI_INT, 0, m->comm));
    wait_end(m);
    int64_t total = 0;
    for (int r = 0; m->rank == 0 && r < m->size; r++) {
        if (total + counts[r] > INT_MAX) fail(m, "over 2 GB to gather");
        displs[r] = (int)total;
        lens[r] = (size_t)counts[r];
        total += counts[r];
    }
    if (m->rank == 0 && !(*all = malloc((size_t)(total ? total : 1)))) fail(m, "out of memory for a gather");
    wait_begin(m);
    check(m, MPI_Gatherv(mine, len, MPI_BYTE, *all, counts, displs, MPI_BYTE, 0, m->comm));
    wait_end(m);
    free(counts), free(displs);
    return SYL_OK;
}

void syl_ecosystem_mpi_end(SylEcoMpi *m) {
    if (!m) return;
    for (int r = 0; m->send && r < m->size; r++) free(m->send[r]), free(m->recv[r]);
    free(m->owner), free(m->next), free(m->box), free(m->send), free(m->recv), free(m->send_len), free(m->recv_len),
        free(m->req);
    MPI_Type_free(&m->plant);
    wait_begin(m); /* MPI_Finalize waits for every rank too */
    MPI_Finalize();
    atomic_store(&m->quit, 1);
    if (m->watching) pthread_join(m->watch, NULL);
    free(m->pid), free(m->host);
    free(m);
}
