/* tools/image_io.h - writes linear RGB float images as PFM (exact) or PNG (8-bit sRGB). */
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
