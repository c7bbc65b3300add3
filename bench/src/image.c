/* Image files: PFM (exact values) and 8-bit sRGB PNG through libpng. */
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tracer.h"

static int host_is_little_endian(void) {
    const uint16_t one = 1;
    unsigned char first;
    memcpy(&first, &one, 1);
    return first == 1;
}

static float swap_float(float f) {
    uint32_t bits;
    memcpy(&bits, &f, 4);
    bits = (bits >> 24) | ((bits >> 8) & 0xFF00u) | ((bits << 8) & 0xFF0000u) | (bits << 24);
    memcpy(&f, &bits, 4);
    return f;
}

bool write_pfm(const char *path, const float *image, uint32_t width, uint32_t height) {
    FILE *f = fopen(path, "wb");
    if (!f) return false;
    /* A negative scale says little-endian; PFM rows run bottom to top. */
    fprintf(f, "PF\n%u %u\n-1.0\n", width, height);
    float *row = malloc(sizeof(float) * 3 * width);
    bool ok = row != NULL;
    for (uint32_t y = height; ok && y-- > 0;) {
        for (uint32_t i = 0; i < 3 * width; ++i) {
            float v = image[(size_t)y * width * 3 + i];
            row[i] = host_is_little_endian() ? v : swap_float(v);
        }
        ok = fwrite(row, sizeof(float), 3 * width, f) == 3 * width;
    }
    free(row);
    return fclose(f) == 0 && ok;
}

float *read_pfm(const char *path, uint32_t *width, uint32_t *height) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char magic[3] = {0};
    unsigned w = 0, h = 0;
    double scale = 0.0;
    float *image = NULL;
    if (fscanf(f, "%2s %u %u %lf", magic, &w, &h, &scale) != 4 || strcmp(magic, "PF") != 0 ||
        w == 0 || h == 0 || w > 16384 || h > 16384 || fgetc(f) == EOF)
        goto done;
    image = malloc(sizeof(float) * 3 * (size_t)w * h);
    if (!image) goto done;
    bool swap = (scale < 0.0) != (host_is_little_endian() != 0);
    for (uint32_t y = h; y-- > 0;) {
        float *row = image + (size_t)y * w * 3;
        if (fread(row, sizeof(float), 3 * (size_t)w, f) != 3 * (size_t)w) {
            free(image);
            image = NULL;
            goto done;
        }
        if (swap)
            for (uint32_t i = 0; i < 3 * w; ++i) row[i] = swap_float(row[i]);
    }
    *width = w;
    *height = h;
done:
    fclose(f);
    return image;
}

/* The sRGB transfer function of a linear value, clamped to [0, 1], as 8 bits. */
static png_byte srgb8(float linear) {
    float v = linear > 0.0f ? (linear < 1.0f ? linear : 1.0f) : 0.0f;
    float s = v <= 0.0031308f ? 12.92f * v : 1.055f * powf(v, 1.0f / 2.4f) - 0.055f;
    return (png_byte)(255.0f * s + 0.5f);
}

/* An 8-bit RGB PNG whose rows `fill` writes (3 bytes per pixel), `context` passed on. */
static bool write_rgb_png(const char *path, uint32_t width, uint32_t height,
                          void (*fill)(png_bytep row, uint32_t y, uint32_t width,
                                       const void *context),
                          const void *context) {
    FILE *f = fopen(path, "wb");
    if (!f) return false;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    png_bytep row = malloc(3 * (size_t)width);
    bool ok = false;
    if (!png || !info || !row) goto done;
    if (setjmp(png_jmpbuf(png))) goto done;
    png_init_io(png, f);
    png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    png_write_info(png, info);
    for (uint32_t y = 0; y < height; ++y) {
        fill(row, y, width, context);
        png_write_row(png, row);
    }
    png_write_end(png, NULL);
    ok = true;
done:
    if (png) png_destroy_write_struct(&png, info ? &info : NULL);
    free(row);
    return fclose(f) == 0 && ok;
}

typedef struct ImageRows {
    const float *image, *reference;
    float scale;
} ImageRows;

static void image_row(png_bytep row, uint32_t y, uint32_t width, const void *context) {
    const ImageRows *r = context;
    for (uint32_t i = 0; i < 3 * width; ++i)
        row[i] = srgb8(r->scale * r->image[(size_t)y * width * 3 + i]);
}

bool write_png(const char *path, const float *image, uint32_t width, uint32_t height,
               float exposure) {
    ImageRows rows = {image, NULL, exp2f(exposure)};
    return write_rgb_png(path, width, height, image_row, &rows);
}

static void error_row(png_bytep row, uint32_t y, uint32_t width, const void *context) {
    const ImageRows *r = context;
    for (uint32_t x = 0; x < width; ++x) {
        size_t i = ((size_t)y * width + x) * 3;
        float e = 0.0f;
        for (int c = 0; c < 3; ++c) e += r->image[i + c] - r->reference[i + c];
        e *= r->scale;
        row[3 * x + 0] = srgb8(e);
        row[3 * x + 1] = 0;
        row[3 * x + 2] = srgb8(-e);
    }
}

bool write_error_png(const char *path, const float *image, const float *reference,
                     uint32_t width, uint32_t height, float exposure) {
    ImageRows rows = {image, reference, exp2f(exposure) * ERROR_IMAGE_GAIN / 3.0f};
    return write_rgb_png(path, width, height, error_row, &rows);
}
