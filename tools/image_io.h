/* tools/image_io.h - writes linear RGB float images as PFM (exact) or PNG (8-bit sRGB), and reads
   PFM back. */
#ifndef VXT_IMAGE_IO_H
#define VXT_IMAGE_IO_H
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* PFM: "PF", width height, -1 (little endian), rows from the bottom. rgb: rows from the top. */
static inline int vxt_write_pfm(const char *path, const float *rgb, int w, int h)
{
    FILE *f = fopen(path, "wb");
    int y, ok;
    if (!f) return -1;
    ok = fprintf(f, "PF\n%d %d\n-1.0\n", w, h) > 0;
    for (y = h - 1; y >= 0 && ok; y--) { /* floats in the host's order: little endian on every machine we build on */
        const unsigned char probe[4] = {1, 0, 0, 0};
        uint32_t one;
        memcpy(&one, probe, 4);
        if (one != 1) { ok = 0; break; }
        ok = fwrite(rgb + (size_t)3 * (size_t)w * (size_t)y, sizeof(float), (size_t)3 * (size_t)w, f) == (size_t)3 * (size_t)w;
    }
    return fclose(f) == 0 && ok ? 0 : -1;
}

/* Reads a colour PFM ("PF", either byte order) into *rgb (rows from the top; free() it). 0 on
   success; else -1 with why in err (a missing file, another format, a short or bad header,
   missing pixels, values that are not finite). */
static inline int vxt_read_pfm(const char *path, float **rgb, int *w, int *h, char *err, size_t err_size)
{
    FILE *f = fopen(path, "rb");
    char magic[3] = {0, 0, 0};
    double scale = 0;
    size_t n = 0, i;
    float *px = NULL;
    int y, little, ok = 0;
    const unsigned char probe[4] = {1, 0, 0, 0};
    uint32_t one;
    *rgb = NULL;
    memcpy(&one, probe, 4);
    if (!f) { snprintf(err, err_size, "%s: cannot open it", path); return -1; }
    if (fread(magic, 1, 2, f) != 2 || strcmp(magic, "PF") != 0) snprintf(err, err_size, "%s: not a colour PFM (no \"PF\")", path);
    else if (fscanf(f, "%d %d %lf", w, h, &scale) != 3 || *w < 1 || *h < 1 || *w > 65536 || *h > 65536 || scale == 0 || !isfinite(scale) ||
             fgetc(f) == EOF)
        snprintf(err, err_size, "%s: a PFM header needs a width and a height (1..65536) and a non-zero scale", path);
    else if (!(px = (float *)malloc((n = (size_t)3 * (size_t)*w * (size_t)*h) * sizeof(float))))
        snprintf(err, err_size, "%s: no memory for %d x %d pixels", path, *w, *h);
    else {
        little = scale < 0;
        ok = 1;
        for (y = *h - 1; y >= 0 && ok; y--) /* rows from the bottom in the file */
            ok = fread(px + (size_t)3 * (size_t)*w * (size_t)y, sizeof(float), (size_t)3 * (size_t)*w, f) == (size_t)3 * (size_t)*w;
        if (!ok) snprintf(err, err_size, "%s: fewer pixels than its %d x %d header says", path, *w, *h);
        for (i = 0; ok && i < n; i++) {
            if ((one == 1) != little) { /* the other byte order */
                unsigned char b[4], t;
                memcpy(b, px + i, 4);
                t = b[0]; b[0] = b[3]; b[3] = t;
                t = b[1]; b[1] = b[2]; b[2] = t;
                memcpy(px + i, b, 4);
            }
            if (!isfinite(px[i])) { ok = 0; snprintf(err, err_size, "%s: pixel %lu is not finite", path, (unsigned long)(i / 3)); }
        }
    }
    fclose(f);
    if (!ok) { free(px); return -1; }
    *rgb = px;
    return 0;
}

static inline uint32_t vxt_crc32(uint32_t crc, const unsigned char *p, size_t n)
{
    size_t i;
    int k;
    crc = ~crc;
    for (i = 0; i < n; i++) {
        crc ^= p[i];
        for (k = 0; k < 8; k++) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

static inline void vxt_put32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24); p[1] = (unsigned char)(v >> 16); p[2] = (unsigned char)(v >> 8); p[3] = (unsigned char)v;
}

static inline int vxt_png_chunk(FILE *f, const char *type, const unsigned char *data, size_t n)
{
    unsigned char head[8], tail[4];
    uint32_t crc;
    vxt_put32(head, (uint32_t)n);
    memcpy(head + 4, type, 4);
    crc = vxt_crc32(vxt_crc32(0, head + 4, 4), data, n);
    vxt_put32(tail, crc);
    return fwrite(head, 1, 8, f) == 8 && (n == 0 || fwrite(data, 1, n, f) == n) && fwrite(tail, 1, 4, f) == 4 ? 0 : -1;
}

/* The sRGB transfer of a linear value in [0, 1], to 8 bits. */
static inline unsigned char vxt_srgb8(float v)
{
    double x = v > 0 ? (v < 1 ? v : 1) : 0;
    x = x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1 / 2.4) - 0.055;
    return (unsigned char)(x * 255 + 0.5);
}

/* PNG, 8-bit RGB: linear values times exposure, clamped, sRGB encoded; zlib with stored
   (uncompressed) blocks, so no compressor is needed. */
static inline int vxt_write_png(const char *path, const float *rgb, int w, int h, float exposure)
{
    size_t row = (size_t)3 * (size_t)w + 1, raw_n = row * (size_t)h, blocks = (raw_n + 65534) / 65535, z_n = 2 + raw_n + 5 * blocks + 4, i, at = 0;
    unsigned char *raw = (unsigned char *)malloc(raw_n), *z = (unsigned char *)malloc(z_n), ihdr[13];
    uint32_t s1 = 1, s2 = 0;
    FILE *f;
    int x, y, rc = -1;
    if (!raw || !z) { free(raw); free(z); return -1; }
    for (y = 0; y < h; y++) {
        raw[row * (size_t)y] = 0; /* filter: none */
        for (x = 0; x < 3 * w; x++) raw[row * (size_t)y + 1 + (size_t)x] = vxt_srgb8(exposure * rgb[(size_t)3 * (size_t)w * (size_t)y + (size_t)x]);
    }
    z[at++] = 0x78; z[at++] = 0x01;
    for (i = 0; i < raw_n; i += 65535) {
        size_t n = raw_n - i < 65535 ? raw_n - i : 65535;
        z[at++] = i + n == raw_n ? 1 : 0;
        z[at++] = (unsigned char)n; z[at++] = (unsigned char)(n >> 8);
        z[at++] = (unsigned char)~n; z[at++] = (unsigned char)(~n >> 8);
        memcpy(z + at, raw + i, n);
        at += n;
    }
    for (i = 0; i < raw_n; i++) { s1 = (s1 + raw[i]) % 65521u; s2 = (s2 + s1) % 65521u; }
    vxt_put32(z + at, s2 << 16 | s1);
    at += 4;
    vxt_put32(ihdr, (uint32_t)w);
    vxt_put32(ihdr + 4, (uint32_t)h);
    ihdr[8] = 8; ihdr[9] = 2; ihdr[10] = ihdr[11] = ihdr[12] = 0;
    if ((f = fopen(path, "wb")) != NULL) {
        static const unsigned char sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
        rc = fwrite(sig, 1, 8, f) == 8 && vxt_png_chunk(f, "IHDR", ihdr, 13) == 0 && vxt_png_chunk(f, "IDAT", z, at) == 0 &&
                     vxt_png_chunk(f, "IEND", NULL, 0) == 0 ? 0 : -1;
        if (fclose(f) != 0) rc = -1;
    }
    free(raw);
    free(z);
    return rc;
}

#endif
