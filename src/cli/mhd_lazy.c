/* libmicrohttpd's table of functions, loaded on first use (cli/mhd_lazy.h). */
#include "cli/mhd_lazy.h"

LAZY_LIB_GETTER(MhdApi, mhd_api, "libmicrohttpd.so.12", "sylva view (its web server)", false, MHD_FUNCS)
