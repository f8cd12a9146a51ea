/* The commands of `sylva`, in the order `sylva --help` lists them. */
#include "cli/cli.h"

const CliCommand *const cli_commands[] = {
    &cli_derive_command, &cli_check_command, &cli_compile_command, &cli_skeleton_command, &cli_mesh_command,
    &cli_render_command, &cli_grow_command,  &cli_compare_command, &cli_convert_command,
    &cli_terrain_command, &cli_animate_command, &cli_ecosystem_command, &cli_describe_command, &cli_view_command,
    NULL,
};
