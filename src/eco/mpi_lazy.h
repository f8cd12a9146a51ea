/* OpenMPI, bound on first use (util/lazylib.h): eco/mpi.c includes this instead of <mpi.h>. */
#ifndef SYL_ECO_MPI_LAZY_H
#define SYL_ECO_MPI_LAZY_H

#include <mpi.h>

#include "util/lazylib.h"

#define MPI_FUNCS(X) \
    X(MPI_Abort) \
    X(MPI_Allgather) \
    X(MPI_Allreduce) \
    X(MPI_Alltoall) \
    X(MPI_Comm_rank) \
    X(MPI_Comm_set_errhandler) \
    X(MPI_Comm_size) \
    X(MPI_Error_string) \
    X(MPI_Finalize) \
    X(MPI_Gather) \
    X(MPI_Gatherv) \
    X(MPI_Init_thread) \
    X(MPI_Irecv) \
    X(MPI_Isend) \
    X(MPI_Type_commit) \
    X(MPI_Type_contiguous) \
    X(MPI_Type_free) \
    X(MPI_Waitall)

typedef struct MpiApi {
    MPI_FUNCS(LAZY_LIB_FIELD)
} MpiApi;
const MpiApi *mpi_api(void);

/* Each call goes through the table; a function missing here is an undefined symbol at link. */
#define MPI_Abort(...) mpi_api()->MPI_Abort(__VA_ARGS__)
#define MPI_Allgather(...) mpi_api()->MPI_Allgather(__VA_ARGS__)
#define MPI_Allreduce(...) mpi_api()->MPI_Allreduce(__VA_ARGS__)
#define MPI_Alltoall(...) mpi_api()->MPI_Alltoall(__VA_ARGS__)
#define MPI_Comm_rank(...) mpi_api()->MPI_Comm_rank(__VA_ARGS__)
#define MPI_Comm_set_errhandler(...) mpi_api()->MPI_Comm_set_errhandler(__VA_ARGS__)
#define MPI_Comm_size(...) mpi_api()->MPI_Comm_size(__VA_ARGS__)
#define MPI_Error_string(...) mpi_api()->MPI_Error_string(__VA_ARGS__)
#define MPI_Finalize(...) mpi_api()->MPI_Finalize(__VA_ARGS__)
#define MPI_Gather(...) mpi_api()->MPI_Gather(__VA_ARGS__)
#define MPI_Gatherv(...) mpi_api()->MPI_Gatherv(__VA_ARGS__)
#define MPI_Init_thread(...) mpi_api()->MPI_Init_thread(__VA_ARGS__)
#define MPI_Irecv(...) mpi_api()->MPI_Irecv(__VA_ARGS__)
#define MPI_Isend(...) mpi_api()->MPI_Isend(__VA_ARGS__)
#define MPI_Type_commit(...) mpi_api()->MPI_Type_commit(__VA_ARGS__)
#define MPI_Type_contiguous(...) mpi_api()->MPI_Type_contiguous(__VA_ARGS__)
#define MPI_Type_free(...) mpi_api()->MPI_Type_free(__VA_ARGS__)
#define MPI_Waitall(...) mpi_api()->MPI_Waitall(__VA_ARGS__)
/* OpenMPI's predefined handles (MPI_COMM_WORLD, MPI_INT, ...) are addresses of its globals. */
#undef OMPI_PREDEFINED_GLOBAL
#define OMPI_PREDEFINED_GLOBAL(type, global) ((type)mpi_global(#global))
void *mpi_global(const char *name);

#endif
