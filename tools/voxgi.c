/* tools/voxgi.c - the voxgi command-line tool: main() and the dispatch to one command per file.
 *
 *   voxgi voxelize MESH [--res N | --grid OX OY OZ SIZE NX NY NZ] [--method M] [--backend B] [-o OUT.binvox] [--json]
 *   voxgi info [--gl KIND] [--json]
 *   voxgi bench voxelize [MESH ...] [--methods LIST] [--min-res N] [--max-res N] [--runs R] [--csv FILE]
 *   voxgi bench rays MESH [--rays N] [--runs R] [--threads T] [--json]
 *   voxgi svo MESH [--res N] [--backend B] [--format F] [--bricks] [--neighbours] [-o FILE.svo] [--json]
 *   voxgi render SCENE|MESH [--method reference|vct|tsm|rsm|sh] [--bounces B] [--spp S] [--camera EX EY EZ TX TY TZ FOVY] [--size W H] -o OUT.png|OUT.pfm
 *   voxgi report vct [--scenes LIST] [--size N] [--res LIST] [--cones LIST] [--apertures LIST] [--steps LIST] [--out DIR]
 *   voxgi report tsm [--scenes LIST] [--size N] [--map-sizes LIST] [--slices LIST] [--samples LIST] [--out DIR]
 *   voxgi report rsm [--scenes LIST] [--size N] [--samples LIST] [--radii LIST] [--points LIST] [--strides LIST] [--visibility LIST] [--out DIR]
 *   voxgi report sh [--scenes LIST] [--size N] [--res LIST] [--openings LIST] [--strides LIST] [--visibility LIST] [--out DIR]
 *   voxgi report ao|ssgi [--scenes LIST] [--size W H] [--rays LIST] [--steps LIST] [--radii LIST] [--res LIST] [--blurs LIST] [--out DIR]
 *   voxgi report linespace [--scenes LIST] [--meshes LIST] [--size N] [--ns LIST] [--depths LIST] [--samples LIST] [--out DIR]
 *   voxgi plan SCENE|MESH [--method M] [--error E] [--res N] [--dynamic] [--budget MB] [--everything]
 *   voxgi report stiff [-o FILE] [--backend B]
 *   voxgi report all [-o|--out DIR] [--quick] [--scenes LIST] [--meshes LIST] [--size N] [--spp S] [--threads T] [--backend B]
 *
 * MESH is an OBJ (+MTL), OFF, STL, PLY or glTF (.gltf, .glb) file, or a built-in shape: builtin:quad,
 * builtin:subdivided-quad, builtin:cube, builtin:sphere. Every command takes --help; tools/cli.h
 * has what they share. */
#include "cli.h"
#include <string.h>

static const char *const main_help =
    "usage: voxgi COMMAND [options]      (voxgi COMMAND --help for each)\n"
    "       voxgi --version              prints the version: voxgi " VOXGI_VERSION_STRING "\n"
    "  voxelize MESH ...   exact conservative voxelization to binvox / JSON\n"
    "  info                version, capabilities, CPU threads and headless GL contexts\n"
    "  bench voxelize ...  timing and voxel-count tables (Buchacher 2014, Tables 1-2)\n"
    "  bench rays MESH     millions of rays per second of the ray core, coherent and incoherent\n"
    "  svo MESH ...        sparse voxel octree: nodes, memory, build time per pass\n"
    "  render SCENE ...    an image of a built-in scene or a mesh (PNG, PFM): the path-traced\n"
    "                      reference, voxel cone tracing, or the light-space passes\n"
    "  report vct ...      cone tracing's error against run time (Markdown, CSV, SVG)\n"
    "  report tsm ...      transmittance shadow maps' error against run time (Markdown, CSV)\n"
    "  report rsm ...      reflective shadow maps' error against run time, and the voxel traversals\n"
    "  report sh ...       the SH volume's error against run time (Markdown, CSV)\n"
    "  report ao|ssgi ...  the screen-space passes' error against run time (Markdown, CSV)\n"
    "  report linespace ... the line space's soft shadows: error, run time, rays (Markdown, CSV)\n"
    "  plan SCENE ...      what a scene needs for a method: each channel, structure and pass kept\n"
    "                      or left out, and why, with its memory\n"
    "  report all ...      every method's error against run time in one report, the fastest method\n"
    "                      reaching each error first (Markdown, CSV, SVG plots, PNG pictures)\n"
    "  report stiff ...    every image method on stiff and extreme input against what is expected\n"
    "Exit status, for every command:\n"
    "  0  success (--help and --version too)\n"
    "  1  failure while running: a mesh that cannot be read, an error from the library, no GL\n"
    "     context for --backend gl, an output that cannot be written; bench: a backend's voxel\n"
    "     count differs from the CPU's\n"
    "  2  usage error, before any work: an unknown command or option, a missing or bad value, an\n"
    "     output file type the command does not write\n";

typedef struct command { const char *name; int (*run)(int argc, char **argv); } command;
static const command commands[] = {{"voxelize", cmd_voxelize}, {"info", cmd_info},     {"bench", cmd_bench},
                                   {"svo", cmd_svo},           {"render", cmd_render}, {"report", cmd_report},
                                   {"plan", cmd_plan}};

int main(int argc, char **argv)
{
    int i;
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "help") == 0) {
        fputs(main_help, argc < 2 ? stderr : stdout);
        return argc < 2 ? CLI_EXIT_USAGE : CLI_EXIT_OK;
    }
    if (strcmp(argv[1], "--version") == 0) {
        printf("voxgi %s\n", VOXGI_VERSION_STRING);
        return CLI_EXIT_OK;
    }
    for (i = 0; i < CLI_COUNT(commands); i++)
        if (strcmp(argv[1], commands[i].name) == 0) return commands[i].run(argc - 2, argv + 2);
    fprintf(stderr, "voxgi: unknown command '%s'\n%s", argv[1], main_help);
    return CLI_EXIT_USAGE;
}
