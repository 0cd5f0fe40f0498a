/*
 * imgrad.h -- the image at a point of the image plane and its gradient
 * there (the first-order paper, Sec. 4-5), for adaptive sampling.
 *
 * The pixel's radiance is emission + direct light + kd/pi E.  Its
 * derivative along the image's x (and y) follows the camera ray as it
 * moves by a pixel (Eq. 26-27 in 3D: the hit moves on the surface it is
 * on, the normal turns with the surface's curvature and its bumps, the
 * view direction turns) and splits, as Eq. 25 does, into
 *   sv   the lighting's spatial variation: the hit moved, its normal and
 *        the view held (SV);
 *   cdv  the normal's turn, curvature and bumps, the rest held (the
 *        curvature-directional term, CDV);
 *   dv   the view direction's turn (the angular term of Eq. 26);
 *   ind  the indirect light's: kd/pi times E's gradient from
 *        irc_cache_lookup_gradient (the records' translational, with their
 *        visibility terms, and rotational gradients) along the hit's move
 *        and the normal's turn.
 * The direct parts are differences over half a pixel of the shading with
 * the light samples and their visibility frozen: the shading integrand's
 * gradient (Sec. 5: "we simply replace the convolutions with the explicit
 * shading calculation for gradients"), not a difference of noisy renders.
 * Shadow edges' own gradient (Sec. 6) is in the indirect part only
 * (frozen direct visibility; the paper's Sec. 5 does the same).
 */
#ifndef EXP_IMGRAD_H
#define EXP_IMGRAD_H

#include "camera.h"
#include "render.h"

typedef struct img_point {
    float rgb[3];
    float indirect[3];   /* rgb's indirect part, kd/pi E */
    int object;          /* what the ray hit (a surface, not a triangle);
                            -1: the environment */
    int lit;             /* 1 when at least half the light samples that face
                            the point reach the light, 0 when fewer, -1
                            when none faces it: where it changes between
                            neighbours, a shadow edge runs (Sec. 6: the
                            visibility gradient is a delta there, Eq. 34) */
    float grad[2][3];    /* dI/dx, dI/dy: radiance per pixel */
    float sv[2][3], cdv[2][3], dv[2][3], ind[2][3]; /* grad's parts */
    /* For the frequency heuristic (Durand et al. 2005, Eq. 20 as the
     * first-order paper quotes it): */
    float curvature;     /* the surface's, without bumps: 1/r on a sphere */
    float depth;         /* along the camera's axis */
    float cos_view;      /* geometric normal . direction to the eye */
    float exponent;      /* the glossy lobe's Phong exponent, 0 if none */
    double grad_s;       /* seconds spent on the gradient */
} img_point;

/* How much gradient image_point computes. */
enum {
    IMG_NO_GRADIENT,
    IMG_GRADIENT_FAST,  /* forward differences over half a pixel (one more
                           surface point an axis), at most 4 of the
                           pixel's light samples: for sampling */
    IMG_GRADIENT,       /* central differences (two an axis), every light
                           sample */
    IMG_GRADIENT_PARTS  /* the same, and its parts (six shadings an axis) */
};

/* The image at (x, y) (pixels from the top-left corner) and, at `grads`
 * (IMG_*), its gradient.  The renderer's light_samples shade it, with the
 * full render's random numbers at pixel centres (render.c) or, when key
 * is not 0, key's everywhere (the same light samples for every point: an
 * image whose differences the gradient must match); its cache (or brute
 * force) gives E.  Returns 0 or a library error. */
int image_point(renderer *r, const cam_frame *cf, float x, float y, int grads, uint64_t key,
                img_point *out);

/* The gradient against the image's own differences: every pixel centre
 * shaded with one set of light samples (so the image is smooth where its
 * light is), each part's luminance gradient (direct: everything but the
 * indirect light; indirect: kd/pi E) against central differences of that
 * part's image, at pixels whose 3 x 3 neighbours see one object.  The
 * indirect image's differences also carry the lookups' weights changing
 * (records entering and leaving reach), which the records' gradients
 * leave out by design. */
typedef struct grad_part {
    int pixels;          /* compared */
    double l2;           /* |grad - difference| over |grad|, summed in L2 */
    int strong;          /* pixels whose |grad| is above 0.1 of the mean */
    double median, p90;  /* their relative errors */
} grad_part;

typedef struct grad_check {
    grad_part direct, indirect;
} grad_check;

int image_gradient_check(renderer *r, const cam_frame *cf, int w, int h, int level,
                         grad_check *out);

/* Luminance of an RGB triple (Rec. 709 weights). */
float lum3(const float c[3]);

#endif
