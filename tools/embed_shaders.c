/* tools/embed_shaders.c - turns voxgi's GLSL sources into a C header.
 *
 *     embed_shaders OUT.h IN1.glsl IN2.glsl ...
 *
 * For each input, sorted by file name whatever the argument order, the header gets a
 * NUL-terminated byte array voxgi__glsl_<stem> (byte arrays, because MSVC caps the length
 * of string literals), and one table voxgi__glsl_files that references them all, so a
 * translation unit that uses none of the arrays still compiles without warnings. Only base
 * names reach the output, which is the same byte for byte on every run. OUT.h is written to
 * a temporary file and renamed into place, so a failed run never leaves half a header.
 *
 * A file of a part that voxgi.h can compile out says so in a line of its own:
 *     // embedded unless VOXGI_NO_A                 left out when VOXGI_NO_A is defined
 *     // embedded unless VOXGI_NO_A or VOXGI_NO_B   ... when either is
 *     // embedded unless VOXGI_NO_A and VOXGI_NO_B  ... only when both are
 * and its array and its table row are wrapped in the matching #if, so that a program without
 * that part carries none of its text. VOXGI__GLSL_FILE_COUNT counts the rows left.
 *
 * Defining EMBED_SHADERS_NO_MAIN before including this file gives embed_shaders() without
 * main(), for tests. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct es_file {
    const char *name; /* base name: the only part of the path that reaches the output */
    char *ident;      /* C identifier: voxgi__glsl_ + the sanitised stem */
    char *guard;      /* the #if that keeps it (its "embedded unless" line), or NULL: always kept */
    unsigned char *data;
    unsigned long size;
} es_file;

static const char *es_base_name(const char *path)
{
    const char *slash = strrchr(path, '/'), *backslash = strrchr(path, '\\');
    if (backslash > slash) slash = backslash;
    return slash ? slash + 1 : path;
}

/* voxgi__glsl_ followed by the name without its last extension, every character outside
 * [A-Za-z0-9_] turned into '_'. */
static char *es_ident(const char *name)
{
    static const char prefix[] = "voxgi__glsl_";
    const char *dot = strrchr(name, '.');
    size_t stem = dot && dot != name ? (size_t)(dot - name) : strlen(name), i;
    char *id = (char *)malloc(sizeof prefix + stem);
    if (!id) return NULL;
    memcpy(id, prefix, sizeof prefix - 1);
    for (i = 0; i < stem; i++) {
        char c = name[i];
        int ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
        id[sizeof prefix - 1 + i] = ok ? c : '_';
    }
    id[sizeof prefix - 1 + stem] = '\0';
    return id;
}

static int es_read(const char *path, es_file *f, char *err, size_t err_size)
{
    FILE *in = fopen(path, "rb");
    size_t cap = 4096, n;
    if (!in) { snprintf(err, err_size, "cannot open %s: %s", path, strerror(errno)); return -1; }
    f->data = (unsigned char *)malloc(cap);
    f->size = 0;
    while (f->data && (n = fread(f->data + f->size, 1, cap - f->size, in)) > 0) {
        f->size += (unsigned long)n;
        if (f->size == cap) {
            unsigned char *grown = (unsigned char *)realloc(f->data, cap *= 2);
            if (!grown) free(f->data);
            f->data = grown;
        }
    }
    if (!f->data) snprintf(err, err_size, "out of memory reading %s", path);
    else if (ferror(in)) snprintf(err, err_size, "cannot read %s: %s", path, strerror(errno));
    if (!f->data || ferror(in)) {
        fclose(in);
        return -1;
    }
    fclose(in);
    return 0;
}

/* Whether the n bytes at s make a part's macro: VOXGI_NO_ and capitals, digits or '_'. */
static int es_macro(const char *s, size_t n)
{
    static const char prefix[] = "VOXGI_NO_";
    size_t i;
    if (n <= sizeof prefix - 1 || memcmp(s, prefix, sizeof prefix - 1) != 0) return 0;
    for (i = sizeof prefix - 1; i < n; i++)
        if (!((s[i] >= 'A' && s[i] <= 'Z') || (s[i] >= '0' && s[i] <= '9') || s[i] == '_')) return 0;
    return 1;
}

/* The "embedded unless" line of f, if any, as the preprocessor line that keeps the file, into
 * f->guard; -1 with a message when the line is malformed or there are two. */
static int es_guard(es_file *f, char *err, size_t err_size)
{
    static const char marker[] = "// embedded unless ";
    const char *text = (const char *)f->data, *end = text + f->size, *line, *eol;
    for (line = text; line < end; line = eol + 1) {
        const char *p, *stop, *word[15];
        size_t len[15], n = 0, k, size = 16;
        int ok;
        eol = (const char *)memchr(line, '\n', (size_t)(end - line));
        if (!eol) eol = end;
        if ((size_t)(eol - line) < sizeof marker - 1 || memcmp(line, marker, sizeof marker - 1) != 0) continue;
        if (f->guard) {
            snprintf(err, err_size, "%s: more than one \"embedded unless\" line", f->name);
            return -1;
        }
        p = line + sizeof marker - 1;
        stop = eol > p && eol[-1] == '\r' ? eol - 1 : eol;
        for (ok = 1; ok; p++) { /* the words, one space apart */
            if (n == 15) { ok = 0; break; }
            word[n] = p;
            while (p < stop && *p != ' ') p++;
            len[n] = (size_t)(p - word[n]);
            size += len[n] + 16;
            n++;
            if (p == stop) break;
        }
        ok = ok && n % 2 == 1; /* NAME, or NAME op NAME ... with the same op throughout */
        for (k = 0; ok && k < n; k++)
            ok = k % 2 == 0 ? es_macro(word[k], len[k])
                            : ((len[k] == 2 && memcmp(word[k], "or", 2) == 0) || (len[k] == 3 && memcmp(word[k], "and", 3) == 0)) &&
                                  len[k] == len[1];
        if (!ok) {
            snprintf(err, err_size, "%s: \"embedded unless\" takes VOXGI_NO_ names joined by \"or\" or by \"and\": %.*s", f->name,
                     (int)(stop - line), line);
            return -1;
        }
        if (!(f->guard = (char *)malloc(size))) {
            snprintf(err, err_size, "out of memory");
            return -1;
        }
        if (n == 1) {
            snprintf(f->guard, size, "#ifndef %.*s", (int)len[0], word[0]);
            continue;
        }
        strcpy(f->guard, "#if");
        for (k = 0; k < n; k += 2) /* "or": kept while none is defined; "and": while one is not */
            sprintf(f->guard + strlen(f->guard), "%s !defined(%.*s)", k == 0 ? "" : len[1] == 2 ? " &&" : " ||", (int)len[k], word[k]);
    }
    return 0;
}

static int es_compare(const void *a, const void *b)
{
    return strcmp(((const es_file *)a)->name, ((const es_file *)b)->name);
}

/* The name as a C string literal. '?' is escaped too, so no trigraph can form. */
static void es_write_string(FILE *out, const char *s)
{
    fputc('"', out);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c >= 0x20 && c < 0x7f && c != '"' && c != '\\' && c != '?') fputc(c, out);
        else fprintf(out, "\\%03o", c);
    }
    fputc('"', out);
}

static void es_write(FILE *out, const es_file *files, int count)
{
    int i;
    unsigned long j;
    fputs("// GENERATED from shaders/*.glsl by tools/embed_shaders.c - DO NOT EDIT: change the .glsl files.\n"
          "#ifndef VOXGI__GLSL_EMBEDDED_H\n"
          "#define VOXGI__GLSL_EMBEDDED_H\n", out);
    for (i = 0; i < count; i++) {
        fprintf(out, "\n%s%sstatic const unsigned char %s[] = {", files[i].guard ? files[i].guard : "", files[i].guard ? "\n" : "",
                files[i].ident);
        for (j = 0; j < files[i].size; j++)
            fprintf(out, "%s0x%02x,", j % 16 ? "" : "\n    ", (unsigned)files[i].data[j]);
        fprintf(out, "%s0x00\n};\n%s", j % 16 ? "" : "\n    ", files[i].guard ? "#endif\n" : "");
    }
    fputs("\ntypedef struct voxgi__glsl_file {\n"
          "    const char *name;\n"
          "    const unsigned char *text; /* NUL-terminated */\n"
          "    unsigned long size;        /* without the NUL */\n"
          "} voxgi__glsl_file;\n\n"
          "static const voxgi__glsl_file voxgi__glsl_files[] = {\n", out);
    for (i = 0; i < count; i++) {
        if (files[i].guard) fprintf(out, "%s\n", files[i].guard);
        fputs("    {", out);
        es_write_string(out, files[i].name);
        fprintf(out, ", %s, %luUL},\n", files[i].ident, files[i].size);
        if (files[i].guard) fputs("#endif\n", out);
    }
    fputs("};\n#define VOXGI__GLSL_FILE_COUNT ((int)(sizeof voxgi__glsl_files / sizeof voxgi__glsl_files[0]))\n\n#endif\n", out);
}

/* Writes out_path from the count files in in_paths. 0 on success; -1 with a message. */
static int embed_shaders(const char *out_path, int count, char **in_paths, char *err, size_t err_size)
{
    es_file *files = (es_file *)calloc(count > 0 ? (size_t)count : 1, sizeof *files);
    char *tmp_path = (char *)malloc(strlen(out_path) + sizeof ".tmp");
    FILE *out = NULL;
    int i, k, rc = -1;

    if (!files || !tmp_path) { snprintf(err, err_size, "out of memory"); goto done; }
    if (count < 1) { snprintf(err, err_size, "no input files"); goto done; }
    for (i = 0; i < count; i++) {
        files[i].name = es_base_name(in_paths[i]);
        files[i].ident = es_ident(files[i].name);
        if (!files[i].ident) { snprintf(err, err_size, "out of memory"); goto done; }
        if (es_read(in_paths[i], &files[i], err, err_size) || es_guard(&files[i], err, err_size)) goto done;
    }
    qsort(files, (size_t)count, sizeof *files, es_compare);
    for (i = 0; i < count; i++)
        for (k = i + 1; k < count; k++)
            if (strcmp(files[i].ident, files[k].ident) == 0) {
                snprintf(err, err_size, "%s and %s would both be named %s", files[i].name,
                         files[k].name, files[i].ident);
                goto done;
            }

    sprintf(tmp_path, "%s.tmp", out_path);
    out = fopen(tmp_path, "wb");
    if (!out) { snprintf(err, err_size, "cannot create %s: %s", tmp_path, strerror(errno)); goto done; }
    es_write(out, files, count);
    i = ferror(out);
    if (fclose(out) != 0 || i) {
        snprintf(err, err_size, "cannot write %s", tmp_path);
        remove(tmp_path);
        goto done;
    }
    if (rename(tmp_path, out_path) != 0) {
        snprintf(err, err_size, "cannot rename %s to %s: %s", tmp_path, out_path, strerror(errno));
        remove(tmp_path);
        goto done;
    }
    rc = 0;
done:
    for (i = 0; files && i < count; i++) {
        free(files[i].ident);
        free(files[i].guard);
        free(files[i].data);
    }
    free(files);
    free(tmp_path);
    return rc;
}

#ifndef EMBED_SHADERS_NO_MAIN
int main(int argc, char **argv)
{
    char err[1024];
    if (argc < 3) {
        fprintf(stderr, "usage: embed_shaders OUT.h IN.glsl...\n");
        return 2;
    }
    if (embed_shaders(argv[1], argc - 2, argv + 2, err, sizeof err) != 0) {
        fprintf(stderr, "embed_shaders: %s\n", err);
        return 1;
    }
    return 0;
}
#endif
