/* tools/image_io.h - writes linear RGB float images as PFM (exact) or PNG (8-bit sRGB), and reads
   PFM back. */
#ifndef VXT_IMAGE_IO_H
#define VXT_IMAGE_IO_H
#include <errno.h>
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

/* Whether f (seekable) holds at least n more bytes from where it stands; it stays there. */
static inline int vxt_stream_holds(FILE *f, size_t n)
{
    long here = ftell(f), end;
    if (here < 0 || fseek(f, 0, SEEK_END) != 0) return 0;
    end = ftell(f);
    if (fseek(f, here, SEEK_SET) != 0) return 0;
    return end >= here && (unsigned long)(end - here) >= n;
}

/* Reads a colour PFM ("PF", either byte order) from f (seekable), from where it stands, into *rgb
   (rows from the top; free() it); name names it in err. 0 on success; else -1 with why in err
   (another format, a short or bad header, missing pixels, values that are not finite). The pixels
   are allocated only once f is known to hold them. f stays open. */
static inline int vxt_read_pfm_stream(FILE *f, const char *name, float **rgb, int *w, int *h, char *err, size_t err_size)
{
    char magic[3] = {0, 0, 0};
    double scale = 0;
    size_t n = 0, i;
    float *px = NULL;
    int y, little, ok = 0;
    const unsigned char probe[4] = {1, 0, 0, 0};
    uint32_t one;
    *rgb = NULL;
    memcpy(&one, probe, 4);
    if (fread(magic, 1, 2, f) != 2 || strcmp(magic, "PF") != 0) snprintf(err, err_size, "%s: not a colour PFM (no \"PF\")", name);
    else if (fscanf(f, "%d %d %lf", w, h, &scale) != 3 || *w < 1 || *h < 1 || *w > 65536 || *h > 65536 || scale == 0 || !isfinite(scale) ||
             fgetc(f) == EOF)
        snprintf(err, err_size, "%s: a PFM header needs a width and a height (1..65536) and a non-zero scale", name);
    else if (!vxt_stream_holds(f, (n = (size_t)3 * (size_t)*w * (size_t)*h) * sizeof(float)))
        snprintf(err, err_size, "%s: fewer pixels than its %d x %d header says", name, *w, *h);
    else if (!(px = (float *)malloc(n * sizeof(float))))
        snprintf(err, err_size, "%s: no memory for %d x %d pixels", name, *w, *h);
    else {
        little = scale < 0;
        ok = 1;
        for (y = *h - 1; y >= 0 && ok; y--) /* rows from the bottom in the file */
            ok = fread(px + (size_t)3 * (size_t)*w * (size_t)y, sizeof(float), (size_t)3 * (size_t)*w, f) == (size_t)3 * (size_t)*w;
        if (!ok) snprintf(err, err_size, "%s: fewer pixels than its %d x %d header says", name, *w, *h);
        for (i = 0; ok && i < n; i++) {
            if ((one == 1) != little) { /* the other byte order */
                unsigned char b[4], t;
                memcpy(b, px + i, 4);
                t = b[0]; b[0] = b[3]; b[3] = t;
                t = b[1]; b[1] = b[2]; b[2] = t;
                memcpy(px + i, b, 4);
            }
            if (!isfinite(px[i])) { ok = 0; snprintf(err, err_size, "%s: pixel %lu is not finite", name, (unsigned long)(i / 3)); }
        }
    }
    if (!ok) { free(px); return -1; }
    *rgb = px;
    return 0;
}

/* vxt_read_pfm_stream of the file at path; also -1 when it cannot be opened. */
static inline int vxt_read_pfm(const char *path, float **rgb, int *w, int *h, char *err, size_t err_size)
{
    FILE *f = fopen(path, "rb");
    int rc;
    *rgb = NULL;
    if (!f) { snprintf(err, err_size, "%s: cannot open it: %s", path, strerror(errno)); return -1; }
    rc = vxt_read_pfm_stream(f, path, rgb, w, h, err, err_size);
    fclose(f);
    return rc;
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

/* ----- deflate (RFC 1951) for the PNGs: LZ77 over a 32 KiB window, matches found through hash
   chains on three bytes (the 64 most recent), coded with the fixed Huffman codes in one block. */
typedef struct vxt_bits {
    unsigned char *p;
    size_t at;
    uint32_t acc; /* bits not yet written, the first in the lowest */
    int n;
} vxt_bits;

static inline void vxt_bits_put(vxt_bits *b, uint32_t v, int n) /* n <= 16 bits, the lowest first */
{
    b->acc |= v << b->n;
    b->n += n;
    while (b->n >= 8) {
        b->p[b->at++] = (unsigned char)b->acc;
        b->acc >>= 8;
        b->n -= 8;
    }
}

static inline void vxt_bits_code(vxt_bits *b, uint32_t code, int len) /* a Huffman code: its highest bit first */
{
    uint32_t r = 0;
    int i;
    for (i = 0; i < len; i++) r |= ((code >> i) & 1u) << (len - 1 - i);
    vxt_bits_put(b, r, len);
}

static inline void vxt_deflate_symbol(vxt_bits *b, int v) /* a literal/length symbol's fixed code */
{
    if (v < 144) vxt_bits_code(b, 0x30u + (uint32_t)v, 8);
    else if (v < 256) vxt_bits_code(b, 0x190u + (uint32_t)(v - 144), 9);
    else if (v < 280) vxt_bits_code(b, (uint32_t)(v - 256), 7);
    else vxt_bits_code(b, 0xC0u + (uint32_t)(v - 280), 8);
}

static const unsigned short vxt_len_base[29] = {3, 4, 5, 6, 7, 8, 9, 10, 11, 13, 15, 17, 19, 23, 27, 31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
static const unsigned char vxt_len_extra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
static const unsigned short vxt_dist_base[30] = {1, 2, 3, 4, 5, 7, 9, 13, 17, 25, 33, 49, 65, 97, 129, 193, 257, 385, 513, 769, 1025, 1537, 2049, 3073,
                                                 4097, 6145, 8193, 12289, 16385, 24577};
static const unsigned char vxt_dist_extra[30] = {0, 0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};

static inline uint32_t vxt_hash3(const unsigned char *p) { return ((uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2]) * 2654435761u >> 17; }

/* The zlib stream (header, one fixed-code block, Adler-32) of d[0..n) into out (room for
   n + n / 8 + 64 bytes: a literal costs at most 9 bits); its length, or 0 without memory. */
static inline size_t vxt_zlib(const unsigned char *d, size_t n, unsigned char *out)
{
    enum { WINDOW = 32768, CHAIN = 64 };
    long *head = (long *)malloc(sizeof(long) << 15), *prev = (long *)malloc(sizeof(long) * WINDOW);
    vxt_bits b = {NULL, 0, 0, 0};
    uint32_t s1 = 1, s2 = 0;
    size_t i = 0, k;
    if (!head || !prev) { free(head); free(prev); return 0; }
    for (k = 0; k < (size_t)1 << 15; k++) head[k] = -1;
    b.p = out;
    vxt_bits_put(&b, 0x78, 8);
    vxt_bits_put(&b, 0x01, 8);
    vxt_bits_put(&b, 3, 3); /* the final block, fixed codes */
    while (i < n) {
        size_t best = 0, dist = 0, step;
        if (i + 3 <= n) {
            long cand = head[vxt_hash3(d + i)];
            int chain = 0;
            while (cand >= 0 && i - (size_t)cand <= WINDOW && chain++ < CHAIN) {
                size_t len = 0, most = n - i < 258 ? n - i : 258;
                while (len < most && d[(size_t)cand + len] == d[i + len]) len++;
                if (len > best) { best = len; dist = i - (size_t)cand; if (len == most) break; }
                if (prev[(size_t)cand % WINDOW] >= cand) break; /* overwritten: the chain ends */
                cand = prev[(size_t)cand % WINDOW];
            }
        }
        if (best >= 3) {
            int c = 28, e = 30;
            while (vxt_len_base[c] > best) c--;
            vxt_deflate_symbol(&b, 257 + c);
            vxt_bits_put(&b, (uint32_t)(best - vxt_len_base[c]), vxt_len_extra[c]);
            while (vxt_dist_base[--e] > dist) {}
            vxt_bits_code(&b, (uint32_t)e, 5);
            vxt_bits_put(&b, (uint32_t)(dist - vxt_dist_base[e]), vxt_dist_extra[e]);
            step = best;
        } else {
            vxt_deflate_symbol(&b, d[i]);
            step = 1;
        }
        for (; step > 0; step--, i++) /* every position the match or literal covers joins its chain */
            if (i + 3 <= n) {
                uint32_t h = vxt_hash3(d + i);
                prev[i % WINDOW] = head[h];
                head[h] = (long)i;
            }
    }
    vxt_deflate_symbol(&b, 256);
    if (b.n) vxt_bits_put(&b, 0, 8 - b.n);
    for (k = 0; k < n; k++) {
        s1 = (s1 + d[k]) % 65521u;
        s2 = (s2 + s1) % 65521u;
    }
    vxt_put32(out + b.at, s2 << 16 | s1);
    free(head);
    free(prev);
    return b.at + 4;
}

/* PNG's Paeth predictor. */
static inline int vxt_paeth(int a, int b, int c)
{
    int p = a + b - c, pa = abs(p - a), pb = abs(p - b), pc = abs(p - c);
    return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

/* PNG, 8-bit RGB from rgb8 (rows from the top): each row filtered by whichever of PNG's five
   filters leaves the smallest sum of magnitudes, then deflated. 0, or -1. */
static inline int vxt_write_png8(const char *path, const unsigned char *rgb8, int w, int h)
{
    size_t stride = (size_t)3 * (size_t)w, row = stride + 1, raw_n = row * (size_t)h, at, x;
    unsigned char *raw = (unsigned char *)malloc(raw_n + 1), *z = (unsigned char *)malloc(raw_n + raw_n / 8 + 64), ihdr[13], *cand = (unsigned char *)malloc(5 * stride + 1);
    FILE *f;
    int y, k, rc = -1;
    if (!raw || !z || !cand) { free(raw); free(z); free(cand); return -1; }
    for (y = 0; y < h; y++) {
        const unsigned char *cur = rgb8 + stride * (size_t)y, *up = y ? cur - stride : NULL;
        unsigned long best = ~0ul;
        int pick = 0;
        for (k = 0; k < 5; k++) {
            unsigned long sum = 0;
            for (x = 0; x < stride; x++) {
                int a = x >= 3 ? cur[x - 3] : 0, b = up ? up[x] : 0, c = x >= 3 && up ? up[x - 3] : 0;
                int pred = k == 0 ? 0 : k == 1 ? a : k == 2 ? b : k == 3 ? (a + b) / 2 : vxt_paeth(a, b, c);
                unsigned char v = (unsigned char)(cur[x] - pred);
                cand[(size_t)k * stride + x] = v;
                sum += v < 128 ? v : 256u - v;
            }
            if (sum < best) { best = sum; pick = k; }
        }
        raw[row * (size_t)y] = (unsigned char)pick;
        memcpy(raw + row * (size_t)y + 1, cand + (size_t)pick * stride, stride);
    }
    at = vxt_zlib(raw, raw_n, z);
    vxt_put32(ihdr, (uint32_t)w);
    vxt_put32(ihdr + 4, (uint32_t)h);
    ihdr[8] = 8; ihdr[9] = 2; ihdr[10] = ihdr[11] = ihdr[12] = 0;
    if (at && (f = fopen(path, "wb")) != NULL) {
        static const unsigned char sig[8] = {137, 80, 78, 71, 13, 10, 26, 10};
        rc = fwrite(sig, 1, 8, f) == 8 && vxt_png_chunk(f, "IHDR", ihdr, 13) == 0 && vxt_png_chunk(f, "IDAT", z, at) == 0 &&
                     vxt_png_chunk(f, "IEND", NULL, 0) == 0 ? 0 : -1;
        if (fclose(f) != 0) rc = -1;
    }
    free(raw);
    free(z);
    free(cand);
    return rc;
}

/* PNG, 8-bit RGB: linear values times exposure, clamped, sRGB encoded. */
static inline int vxt_write_png(const char *path, const float *rgb, int w, int h, float exposure)
{
    size_t i, n = (size_t)3 * (size_t)w * (size_t)h;
    unsigned char *px = (unsigned char *)malloc(n + 1);
    int rc;
    if (!px) return -1;
    for (i = 0; i < n; i++) px[i] = vxt_srgb8(exposure * rgb[i]);
    rc = vxt_write_png8(path, px, w, h);
    free(px);
    return rc;
}

#endif
