/*
 * records.c -- the records view (render_records, render.h): each pixel
 * coloured by the record of largest weight there, centres in white.
 */
#define IRC_EXPERIMENTAL /* irc_cache_neighbours (irrcache.h) */
#include <float.h>
#include <math.h>
#include <string.h>

#include "camera.h"
#include "render.h"

static void hue(uint32_t id, float out[3])
{
    double h = (double)(hash64(id) >> 11) * (6.0 / 9007199254740992.0);
    int i = (int)h;
    float f = (float)(h - i), q = 1.0f - f;
    float tab[6][3] = {{1, f, 0}, {q, 1, 0}, {0, 1, f}, {0, q, 1}, {f, 0, 1}, {1, 0, q}};
    memcpy(out, tab[i % 6], 3 * sizeof(float));
}

int render_records(renderer *r, float *rgb)
{
    const camera *c = &r->s->cam;
    cam_frame cf;
    irc_stats cs;
    uint32_t ids[256], cnt, k, id;
    int x, y, i;
    if (!r->cache)
        return -1;
    camera_frame(c, &cf);
    for (y = 0; y < c->height; y++)
        for (x = 0; x < c->width; x++) {
            float d[3], p[3], *out = &rgb[((size_t)y * c->width + x) * 3], best = 0.0f;
            bvh_hit bh;
            surface sf;
            out[0] = out[1] = out[2] = 0.0f;
            camera_ray(&cf, c, x, y, d);
            if (!bvh_intersect(&r->b, cf.eye, d, 0.0f, FLT_MAX, &bh))
                continue;
            surface_at(r->s, cf.eye, d, &bh, &sf);
            cache_point(&sf, p);
            irc_cache_neighbours(r->cache, p, sf.nsm, ids, 256, &cnt);
            for (k = 0; k < cnt && k < 256; k++) {
                irc_record rec;
                float dd = 0.0f, nn = 0.0f, w;
                irc_cache_record(r->cache, ids[k], &rec);
                for (i = 0; i < 3; i++) {
                    dd += (p[i] - rec.p[i]) * (p[i] - rec.p[i]);
                    nn += sf.nsm[i] * rec.n[i];
                }
                w = 1.0f / (sqrtf(dd) / rec.radius + sqrtf(nn < 1.0f ? 1.0f - nn : 0.0f) + 1e-6f);
                if (w > best) {
                    best = w;
                    hue(ids[k], out);
                    for (i = 0; i < 3; i++)
                        out[i] *= 0.6f;
                }
            }
        }
    irc_cache_stats(r->cache, &cs);
    for (id = 0; id < cs.records; id++) {
        irc_record rec;
        float v[3], z, dist, sx, sy;
        int px, py;
        irc_cache_record(r->cache, id, &rec);
        for (i = 0; i < 3; i++)
            v[i] = rec.p[i] - cf.eye[i];
        z = v[0] * cf.f[0] + v[1] * cf.f[1] + v[2] * cf.f[2];
        if (z <= 0.0f)
            continue;
        dist = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        for (i = 0; i < 3; i++)
            v[i] /= dist;
        if (bvh_occluded(&r->b, cf.eye, v, 0.0f, dist * (1.0f - 1e-3f)))
            continue;
        sx = (v[0] * cf.right[0] + v[1] * cf.right[1] + v[2] * cf.right[2]) / (z / dist) / cf.tx;
        sy = (v[0] * cf.up[0] + v[1] * cf.up[1] + v[2] * cf.up[2]) / (z / dist) / cf.ty;
        px = (int)((sx + 1.0f) * 0.5f * c->width);
        py = (int)((1.0f - sy) * 0.5f * c->height);
        if (px >= 0 && px < c->width && py >= 0 && py < c->height)
            for (i = 0; i < 3; i++)
                rgb[((size_t)py * c->width + px) * 3 + i] = 1.0f;
    }
    return 0;
}
