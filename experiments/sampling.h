/*
 * sampling.h -- adaptive image sampling as the first-order paper places its
 * samples (Ramamoorthi, Mahajan, Belhumeur 2007, Sec. 5), and the
 * reconstruction of an image from scattered samples.
 *
 * The image starts as blocks of `block` pixels, one sample at each centre
 * plus samples on the image's border (so the reconstruction covers every
 * pixel).  Each sample is the centre of a square; a square's importance is
 * its sample's importance density times the square's area.  The square of
 * greatest importance is split into four, each with a new sample at its
 * centre, until the samples reach the budget.  Squares whose sample sees
 * another object than its parent's or a neighbouring block's (an object
 * boundary) are split first, down to min_side.  The samples are then
 * triangulated (Delaunay, exact integer predicates) and the image
 * interpolated linearly on the triangles.
 */
#ifndef EXP_SAMPLING_H
#define EXP_SAMPLING_H

typedef struct ad_sample {
    float x, y;        /* in pixels: (0, 0) is the image's top-left corner,
                          pixel (i, j)'s centre is (i + 0.5, j + 0.5) */
    float rgb[3];
    float importance;  /* per unit area, >= 0 (the metric's) */
    int object;        /* what the sample sees; squares whose samples see
                          different objects are split first */
    int region;        /* a part of the object (e.g. lit or in shadow):
                          a square whose sample's region differs from a
                          sibling's, its parent's or a neighbour's on the
                          same object gets at least |delta luminance| /
                          side as its importance */
} ad_sample;

/* Fills out->rgb, ->importance and ->object for the sample at (x, y) (x
 * and y are set already).  Returns 0, or a negative value that stops the
 * sampling. */
typedef int (*ad_eval_fn)(void *ctx, ad_sample *out);

typedef struct ad_opts {
    int width, height;   /* multiples of block */
    int block;           /* the first squares' side (8 in the paper) */
    double budget;       /* samples as a fraction of width x height */
    float min_side;      /* 1, 0.5 or 0.25 pixels: squares are not split
                            below it */
    int at_pixels;       /* 1: every sample at a pixel centre, the one
                            holding its square's centre (lower right at a
                            corner), the border's at the outermost
                            pixels' (samples then match a full render's
                            pixels; min_side must be 1); 0: at the
                            squares' centres and the image's border */
} ad_opts;

/* Places the samples.  *out (malloc'd, the caller frees it) gets them and
 * *count their number, at most the budget plus 3.  Returns 0, -1 for bad
 * options or no memory, or the evaluator's negative value. */
int adaptive_sample(const ad_opts *o, ad_eval_fn eval, void *ctx, ad_sample **out, int *count);

/* Reconstructs a width x height RGB image (rows top down) from samples
 * inside [0, width] x [0, height] whose bounding box holds every pixel
 * centre and has its four corners among them (as adaptive_sample's do),
 * every position a multiple of unit (a power of two, at most 1) with
 * width / unit <= 8192: the Delaunay triangulation of the positions, each
 * pixel centre interpolated linearly in its triangle.
 * Returns 0, or -1 for bad input or no memory. */
int adaptive_reconstruct(const ad_sample *s, int n, int width, int height, float unit,
                         float *rgb);

/* The Delaunay triangulation itself, for tests: n points on an integer
 * grid (|x|, |y| <= 8192, no two equal) whose hull is the rectangle of the
 * first four, which are its corners.  *tri (malloc'd) gets 3 indices a
 * triangle, counter-clockwise in a y-up frame, *ntri their number.
 * Returns 0, or -1 for bad input or no memory. */
int delaunay(const long long *xy, int n, int **tri, int *ntri);

#endif
