/* t_pixel_footprint.c -- irc_pixel_footprint against the area a pixel covers. */
#include <float.h>
#include <math.h>

#include "irrcache.h"
#include "test.h"

/* Intersects the ray from the origin through (x, y, 1) with the plane
 * through q of normal m. */
static void on_plane(double x, double y, const double q[3], const double m[3], double out[3])
{
    const double d[3] = {x, y, 1.0};
    double t = (q[0] * m[0] + q[1] * m[1] + q[2] * m[2]) / (d[0] * m[0] + d[1] * m[1] + d[2] * m[2]);
    int i;
    for (i = 0; i < 3; i++)
        out[i] = t * d[i];
}

/* irc_pixel_footprint against the area a pixel really covers: a camera at
 * the origin looking along +z, pixels of width s on the plane z = 1; the
 * pixel's corners cast onto the tilted surface span |dp/dx x dp/dy|, whose
 * square root is the footprint (differences of 1e-3 pixels, so the
 * parallelogram is the pixel's to 1e-3).  Then the grazing clamp, the
 * sign of n, and the refusals. */
TEST(test_pixel_footprint)
{
    const float eye[3] = {0, 0, 0}, fwd[3] = {0, 0, 2}, s = 0.004f;
    float fp = -1.0f, worst = 0.0f;
    int i;
    for (i = 0; i < 200; i++) {
        /* pixels across a 70-degree view, surfaces tilted up to 80 degrees */
        const double x = -0.7 + 1.4 * ((i * 37) % 200) / 200.0, y = -0.5 + (i % 20) / 20.0;
        const double dist = 0.5 + 0.1 * i, h = 1e-3 * s, len = sqrt(x * x + y * y + 1.0);
        const double tilt = 1.4 * ((i * 13) % 100) / 100.0, az = 0.7 * i;
        double m[3], q[3], a[3], b[3], c0[3], u[3], v[3], w[3], area, back[3];
        float p[3], n[3];
        int k;
        for (k = 0; k < 3; k++)
            back[k] = -(k == 0 ? x : k == 1 ? y : 1.0) / len;
        /* the normal: the direction back to the eye turned by tilt */
        {
            double t1[3] = {back[1], -back[0], 0.0}, l1 = sqrt(t1[0] * t1[0] + t1[1] * t1[1]);
            double t2[3];
            for (k = 0; k < 3; k++)
                t1[k] /= l1;
            t2[0] = back[1] * t1[2] - back[2] * t1[1];
            t2[1] = back[2] * t1[0] - back[0] * t1[2];
            t2[2] = back[0] * t1[1] - back[1] * t1[0];
            for (k = 0; k < 3; k++)
                m[k] = cos(tilt) * back[k] + sin(tilt) * (cos(az) * t1[k] + sin(az) * t2[k]);
        }
        for (k = 0; k < 3; k++)
            q[k] = -back[k] * dist;
        on_plane(x, y, q, m, c0);
        on_plane(x + h, y, q, m, a);
        on_plane(x, y + h, q, m, b);
        for (k = 0; k < 3; k++) {
            u[k] = (a[k] - c0[k]) / 1e-3;
            v[k] = (b[k] - c0[k]) / 1e-3;
            p[k] = (float)c0[k];
            n[k] = (float)(i % 2 ? m[k] : -m[k]); /* either side */
        }
        w[0] = u[1] * v[2] - u[2] * v[1];
        w[1] = u[2] * v[0] - u[0] * v[2];
        w[2] = u[0] * v[1] - u[1] * v[0];
        area = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        CHECK(irc_pixel_footprint(eye, fwd, s, p, n, &fp) == IRC_OK, "call %d", i);
        if (fabs(fp / sqrt(area) - 1.0) > worst)
            worst = (float)fabs(fp / sqrt(area) - 1.0);
    }
    printf("  200 pixels: worst relative difference from the cast pixel %.2e\n", worst);
    CHECK(worst < 2e-3, "footprint off by %g", worst);
    {
        /* grazing: |d.n| = 0.01 gives the footprint of 0.05 */
        const float p[3] = {0, 0, 5}, n1[3] = {0, 0.99995f, 0.01f}, n2[3] = {0, 0.99875f, 0.05f};
        float f1, f2;
        CHECK(irc_pixel_footprint(eye, fwd, s, p, n1, &f1) == IRC_OK &&
                  irc_pixel_footprint(eye, fwd, s, p, n2, &f2) == IRC_OK &&
                  fabsf(f1 / f2 - 1.0f) < 1e-3f,
              "grazing %g against %g", f1, f2);
    }
    {
        const float p[3] = {0, 0, 5}, n[3] = {0, 0, 1}, behind[3] = {0, 0, -5}, zero[3] = {0, 0, 0};
        const float bad[3] = {0, NAN, 5};
        fp = 7.0f;
        CHECK(irc_pixel_footprint(NULL, fwd, s, p, n, &fp) == IRC_ERR_NULL, "null eye");
        CHECK(irc_pixel_footprint(eye, fwd, s, p, n, NULL) == IRC_ERR_NULL, "null out");
        CHECK(irc_pixel_footprint(eye, fwd, s, bad, n, &fp) == IRC_ERR_NONFINITE, "nan p");
        CHECK(irc_pixel_footprint(eye, fwd, INFINITY, p, n, &fp) == IRC_ERR_NONFINITE, "inf angle");
        CHECK(irc_pixel_footprint(eye, fwd, s, p, zero, &fp) == IRC_ERR_NORMAL, "zero normal");
        CHECK(irc_pixel_footprint(eye, fwd, 0.0f, p, n, &fp) == IRC_ERR_RANGE, "zero angle");
        CHECK(irc_pixel_footprint(eye, zero, s, p, n, &fp) == IRC_ERR_RANGE, "zero forward");
        CHECK(irc_pixel_footprint(eye, fwd, s, eye, n, &fp) == IRC_ERR_RANGE, "p at eye");
        CHECK(irc_pixel_footprint(eye, fwd, s, behind, n, &fp) == IRC_ERR_RANGE, "behind");
        CHECK(irc_pixel_footprint(eye, NULL, s, p, n, &fp) == IRC_ERR_NULL, "null forward");
        CHECK(irc_pixel_footprint(eye, fwd, s, NULL, n, &fp) == IRC_ERR_NULL, "null p");
        CHECK(irc_pixel_footprint(eye, fwd, s, p, NULL, &fp) == IRC_ERR_NULL, "null n");
        CHECK(irc_pixel_footprint(bad, fwd, s, p, n, &fp) == IRC_ERR_NONFINITE, "nan eye");
        CHECK(irc_pixel_footprint(eye, bad, s, p, n, &fp) == IRC_ERR_NONFINITE, "nan forward");
        CHECK(irc_pixel_footprint(eye, fwd, NAN, p, n, &fp) == IRC_ERR_NONFINITE, "nan angle");
        CHECK(irc_pixel_footprint(eye, fwd, s, p, bad, &fp) == IRC_ERR_NORMAL, "nan normal");
        CHECK(irc_pixel_footprint(eye, fwd, -s, p, n, &fp) == IRC_ERR_RANGE, "negative angle");
        CHECK(fp == 7.0f, "a refused call wrote %g", fp);
    }
}

/* The header's "forward (any length)" and any n not zero: scaling forward
 * or n by any finite non-zero factor, and moving p and the eye together
 * by any finite amount, leaves the footprint as it was; p k times farther
 * along the same ray gives k times the footprint, until float overflows
 * (IRC_ERR_NONFINITE then, nothing written). */
TEST(test_pixel_footprint_lengths)
{
    const float eye[3] = {0, 0, 0}, fwd[3] = {0.1f, 0.2f, 2.0f}, s = 0.004f;
    const float p[3] = {0.5f, -0.3f, 4.0f}, n[3] = {0.2f, 0.3f, -0.9f};
    static const float scales[] = {1e-38f, 1e-30f, 1e-19f, 1e-10f, 1e10f, 1e19f, 1e30f, 1.5e38f};
    float base, fp;
    unsigned i;
    int k;
    CHECK(irc_pixel_footprint(eye, fwd, s, p, n, &base) == IRC_OK && base > 0.0f, "base call");
    for (i = 0; i < sizeof scales / sizeof scales[0]; i++) {
        float f2[3], n2[3];
        for (k = 0; k < 3; k++) {
            f2[k] = fwd[k] * scales[i];
            n2[k] = n[k] * scales[i];
        }
        fp = -1.0f;
        CHECK(irc_pixel_footprint(eye, f2, s, p, n, &fp) == IRC_OK && fabsf(fp / base - 1.0f) < 1e-5f,
              "forward x %g: %g against %g", (double)scales[i], (double)fp, (double)base);
        fp = -1.0f;
        CHECK(irc_pixel_footprint(eye, fwd, s, p, n2, &fp) == IRC_OK && fabsf(fp / base - 1.0f) < 1e-5f,
              "n x %g: %g against %g", (double)scales[i], (double)fp, (double)base);
    }
    {
        /* p and the eye far from the origin, and p far from the eye */
        const float far_eye[3] = {1e25f, -1e25f, 3e25f};
        float fp_far = -1.0f, p2[3], p3[3], e3[3];
        for (k = 0; k < 3; k++) {
            p2[k] = p[k] * 1e30f;
            e3[k] = -1e38f * fwd[k] / fwd[2];
            p3[k] = 1e38f * fwd[k] / fwd[2];
        }
        CHECK(irc_pixel_footprint(eye, fwd, s, p2, n, &fp_far) == IRC_OK &&
                  fabsf(fp_far / (base * 1e30f) - 1.0f) < 1e-5f,
              "p at 1e30: %g against %g", (double)fp_far, (double)base * 1e30);
        for (k = 0; k < 3; k++)
            p2[k] = far_eye[k] + p[k] * 1e22f;
        CHECK(irc_pixel_footprint(far_eye, fwd, s, p2, n, &fp_far) == IRC_OK &&
                  fabsf(fp_far / (base * 1e22f) - 1.0f) < 1e-3f,
              "eye at 1e25: %g against %g", (double)fp_far, (double)base * 1e22);
        /* 2e38 from the eye along forward: finite; pixel_angle 1e3 makes
         * the footprint overflow */
        fp = 7.0f;
        CHECK(irc_pixel_footprint(e3, fwd, s, p3, n, &fp) == IRC_OK && fp > 0.0f && fp < FLT_MAX,
              "p 2e38 from the eye: %g", (double)fp);
        fp = 7.0f;
        CHECK(irc_pixel_footprint(e3, fwd, 1e3f, p3, n, &fp) == IRC_ERR_NONFINITE && fp == 7.0f,
              "overflowing footprint");
    }
}

/* The header's rule for a point seen through a flat mirror: the unfolded
 * path gives the footprint the point would have if the mirror image were
 * seen directly.  Camera at the origin along +z (tilted), a mirror in the
 * plane z = 5 facing the camera, a surface point p in front of it at z =
 * 3 (its image p' at z = 7).  With forward reflected the two agree; with
 * forward = d the footprint is wider by at most 1/(d0.f)^(3/2). */
TEST(test_pixel_footprint_mirror)
{
    const float eye[3] = {0, 0, 0}, fwd[3] = {0.1f, -0.05f, 1.0f}, s = 0.003f;
    const float img[3] = {0.8f, 0.5f, 7.0f}, n_img[3] = {0.3f, -0.2f, -0.93f};
    float p[3], n[3], d[3], d0[3], eye2[3], fwd_r[3], direct, folded, along_d, len0, len1, L, dn;
    int k;
    /* the mirror image of p' and n' across z = 5 */
    for (k = 0; k < 3; k++) {
        p[k] = img[k];
        n[k] = n_img[k];
        fwd_r[k] = fwd[k];
    }
    p[2] = 10.0f - img[2];
    n[2] = -n_img[2];
    fwd_r[2] = -fwd[2];
    /* the camera ray hits the mirror at t0; the reflected ray reaches p */
    len0 = 5.0f / img[2];
    for (k = 0; k < 3; k++)
        d0[k] = img[k];
    L = sqrtf(d0[0] * d0[0] + d0[1] * d0[1] + d0[2] * d0[2]); /* |p' - eye| */
    len1 = L * (1.0f - len0);
    for (k = 0; k < 3; k++) {
        const float hit = img[k] * len0;
        d[k] = (p[k] - hit) / len1;
    }
    for (k = 0; k < 3; k++)
        eye2[k] = p[k] - L * d[k];
    CHECK(irc_pixel_footprint(eye, fwd, s, img, n_img, &direct) == IRC_OK, "direct");
    CHECK(irc_pixel_footprint(eye2, fwd_r, s, p, n, &folded) == IRC_OK, "folded");
    CHECK(irc_pixel_footprint(eye2, d, s, p, n, &along_d) == IRC_OK, "along d");
    CHECK(fabsf(folded / direct - 1.0f) < 1e-4f, "unfolded %g against direct %g", (double)folded,
          (double)direct);
    dn = (d0[0] * fwd[0] + d0[1] * fwd[1] + d0[2] * fwd[2]) /
         (L * sqrtf(fwd[0] * fwd[0] + fwd[1] * fwd[1] + fwd[2] * fwd[2]));
    CHECK(along_d >= direct * (1.0f - 1e-5f) && along_d <= direct / (dn * sqrtf(dn)) * (1.0f + 1e-4f),
          "forward = d: %g outside [%g, %g]", (double)along_d, (double)direct,
          (double)(direct / (dn * sqrtf(dn))));
}
