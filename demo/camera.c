/*
 * camera.c -- the pinhole camera's frame and rays, and the point the cache
 * sees for a surface.
 */
#include "camera.h"
#include "irrcache.h"

#include <math.h>

#define PI 3.14159265358979323846

void camera_frame(const camera *c, cam_frame *cf)
{
    float l;
    int i;
    for (i = 0; i < 3; i++)
        cf->f[i] = c->look[i] - c->eye[i];
    l = sqrtf(cf->f[0] * cf->f[0] + cf->f[1] * cf->f[1] + cf->f[2] * cf->f[2]);
    for (i = 0; i < 3; i++) {
        cf->f[i] /= l;
        cf->eye[i] = c->eye[i];
    }
    cf->right[0] = cf->f[1] * c->up[2] - cf->f[2] * c->up[1];
    cf->right[1] = cf->f[2] * c->up[0] - cf->f[0] * c->up[2];
    cf->right[2] = cf->f[0] * c->up[1] - cf->f[1] * c->up[0];
    l = sqrtf(cf->right[0] * cf->right[0] + cf->right[1] * cf->right[1] +
              cf->right[2] * cf->right[2]);
    for (i = 0; i < 3; i++)
        cf->right[i] /= l;
    cf->up[0] = cf->right[1] * cf->f[2] - cf->right[2] * cf->f[1];
    cf->up[1] = cf->right[2] * cf->f[0] - cf->right[0] * cf->f[2];
    cf->up[2] = cf->right[0] * cf->f[1] - cf->right[1] * cf->f[0];
    cf->ty = tanf(0.5f * c->fov_deg * (float)(PI / 180.0));
    cf->tx = cf->ty * (float)c->width / (float)c->height;
}

void camera_ray(const cam_frame *cf, const camera *c, int x, int y, float d[3])
{
    camera_ray_at(cf, c, x + 0.5f, y + 0.5f, d);
}

void camera_ray_at(const cam_frame *cf, const camera *c, float x, float y, float d[3])
{
    float sx = (2.0f * x / c->width - 1.0f) * cf->tx;
    float sy = (1.0f - 2.0f * y / c->height) * cf->ty, l;
    int i;
    for (i = 0; i < 3; i++)
        d[i] = cf->f[i] + sx * cf->right[i] + sy * cf->up[i];
    l = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (i = 0; i < 3; i++)
        d[i] /= l;
}

float camera_footprint(const cam_frame *cf, const camera *c, const float d[3], float t,
                       const float n[3])
{
    /* a pixel is 2 ty / H wide on the image plane at distance 1 along f;
     * the library's rule turns that into its width at the hit */
    float p[3], fp = 0.0f;
    int i;
    for (i = 0; i < 3; i++)
        p[i] = cf->eye[i] + t * d[i];
    if (irc_pixel_footprint(cf->eye, cf->f, 2.0f * cf->ty / (float)c->height, p, n, &fp) < 0)
        return 0.0f; /* no pixel bound */
    return fp;
}

/* The point the cache sees for a surface: lifted off it so that hemisphere
 * rays start clear of it. */
void cache_point(const surface *sf, float p[3])
{
    int i;
    for (i = 0; i < 3; i++)
        p[i] = sf->p[i] + ray_offset(sf->p) * sf->ng[i];
}

