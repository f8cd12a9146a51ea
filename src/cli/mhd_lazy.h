/* libmicrohttpd, bound on first use (util/lazylib.h): `sylva view` includes this instead of <microhttpd.h>. */
#ifndef SYL_CLI_MHD_LAZY_H
#define SYL_CLI_MHD_LAZY_H

#include <microhttpd.h>

#include "util/lazylib.h"

#define MHD_FUNCS(X) \
    X(MHD_add_response_header) \
    X(MHD_create_response_from_buffer) \
    X(MHD_create_response_from_callback) \
    X(MHD_create_response_from_fd) \
    X(MHD_destroy_response) \
    X(MHD_get_connection_values) \
    X(MHD_get_daemon_info) \
    X(MHD_lookup_connection_value) \
    X(MHD_queue_response) \
    X(MHD_start_daemon) \
    X(MHD_stop_daemon)

typedef struct MhdApi {
    MHD_FUNCS(LAZY_LIB_FIELD)
} MhdApi;
const MhdApi *mhd_api(void);

/* Each call goes through the table; a function missing here is an undefined symbol at link. */
#define MHD_add_response_header(...) mhd_api()->MHD_add_response_header(__VA_ARGS__)
#define MHD_create_response_from_buffer(...) mhd_api()->MHD_create_response_from_buffer(__VA_ARGS__)
#define MHD_create_response_from_callback(...) mhd_api()->MHD_create_response_from_callback(__VA_ARGS__)
#define MHD_create_response_from_fd(...) mhd_api()->MHD_create_response_from_fd(__VA_ARGS__)
#define MHD_destroy_response(...) mhd_api()->MHD_destroy_response(__VA_ARGS__)
#define MHD_get_connection_values(...) mhd_api()->MHD_get_connection_values(__VA_ARGS__)
#define MHD_get_daemon_info(...) mhd_api()->MHD_get_daemon_info(__VA_ARGS__)
#define MHD_lookup_connection_value(...) mhd_api()->MHD_lookup_connection_value(__VA_ARGS__)
#define MHD_queue_response(...) mhd_api()->MHD_queue_response(__VA_ARGS__)
#define MHD_start_daemon(...) mhd_api()->MHD_start_daemon(__VA_ARGS__)
#define MHD_stop_daemon(...) mhd_api()->MHD_stop_daemon(__VA_ARGS__)

#endif
