/* tools/cmd_info.c - voxgi info: the version, capabilities, CPU threads and headless GL contexts. */
#include "cli.h"
#include <string.h>

static const char *const info_help =
    "usage: voxgi info [--gl auto|egl|osmesa] [--json]\n"
    "Prints the version, the compiled-in capabilities, the CPU threads and, for each way of making\n"
    "a headless GL context, whether a GL 4.5 context works and which renderer it has. A software\n"
    "rasteriser (llvmpipe, SwiftShader, ...) runs on the CPU's own cores: --backend auto then\n"
    "picks the CPU, which is faster there.\n";

int cmd_info(int argc, char **argv)
{
    static const vxt_gl_kind kinds[2] = {VXT_GL_EGL, VXT_GL_OSMESA};
    cli_common common;
    cli_session s;
    cli_context cpu;
    voxgi_info ci;
    int k, rc, listed = 0;
    memset(&common, 0, sizeof common);
    {
        const cli_option options[] = {
            CLI_OPT_GL(&common, "only this way of making a GL context (default auto: egl and osmesa)"),
            CLI_OPT_JSON(&common, "print one JSON object instead of text")};
        const cli_command cmd = {.name = "info", .help = info_help, .column = 27, .options = options, .option_count = CLI_COUNT(options)};
        if ((rc = cli_parse(&cmd, argc, argv)) != CLI_CONTINUE) return rc;
    }
    cli_session_init(&s, "info");
    if (cli_context_open(&s, &cpu, VOXGI_BACKEND_CPU, VXT_GL_AUTO, 0, 0)) return CLI_EXIT_FAILURE;
    voxgi_query_info(cpu.vx, &ci);
    if (common.json) printf("{\"version\":%s,\"capabilities\":%s,\"cpu_threads\":%d,\"gl\":[", cli_json(VOXGI_VERSION_STRING), cli_json(ci.capabilities), ci.thread_count);
    else printf("voxgi %s\ncapabilities: %s\ncpu: %d worker threads\n", VOXGI_VERSION_STRING, ci.capabilities, ci.thread_count);
    cli_context_close(&s, &cpu);
    for (k = 0; k < 2; k++) {
        cli_context c;
        int ok;
        if (common.gl != VXT_GL_AUTO && common.gl != (int)kinds[k]) continue;
        ok = cli_context_try(&s, &c, VOXGI_BACKEND_GL, kinds[k], 0, 0) == 0;
        if (ok) voxgi_query_info(c.vx, &ci);
        if (common.json) {
            printf("%s{\"context\":%s,\"ok\":%s,\"version\":%s,\"renderer\":%s,\"software\":%s,\"error\":%s}", listed++ ? "," : "",
                   cli_json(k ? "osmesa" : "egl"), ok ? "true" : "false", cli_json(ok ? ci.gl_version : ""), cli_json(ok ? ci.gl_renderer : ""),
                   ok && ci.gl_software ? "true" : "false", cli_json(ok ? "" : s.error));
        } else if (ok)
            printf("gl (%s): %s, %s%s\n", k ? "osmesa" : "egl", ci.gl_version, ci.gl_renderer,
                   ci.gl_software ? " (software rasteriser on the CPU's cores: --backend auto picks the CPU; GL timings are not GPU timings)" : "");
        else printf("gl (%s): not available: %s\n", k ? "osmesa" : "egl", s.error);
        if (ok) cli_context_close(&s, &c);
    }
    if (common.json) printf("]}\n");
    return CLI_EXIT_OK;
}
