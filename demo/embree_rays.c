/*
 * embree_rays.c -- the scene's triangles traced by Embree 3 behind the
 * demo's bvh_intersect and bvh_occluded (bvh.h, bvh_rays), so that the
 * bench measures the cache where a production host's rays are: several
 * times faster than the demo's own BVH, which hides the library's cost.
 * Built into the bench only, and only where Embree is installed (make
 * bench installs libembree-dev from Debian's packages as root).
 *
 * One device a renderer, its build on the calling thread ("threads=1"):
 * no worker threads left to spin in the process's CPU time, which is
 * what the bench compares.  Hits are Embree's (t, primID, and u, v, the
 * barycentrics of v[1] and v[2], as the demo's are); any hit the same.
 */
#include <embree3/rtcore.h>
#include <stdio.h>
#include <stdlib.h>

#include "bvh.h"

typedef struct fast {
    RTCDevice dev;
    RTCScene scene;
} fast;

static void fast_release(void *ctx)
{
    fast *f = (fast *)ctx;
    if (f->scene)
        rtcReleaseScene(f->scene);
    if (f->dev)
        rtcReleaseDevice(f->dev);
    free(f);
}

static void fast_ray(struct RTCRay *r, const float o[3], const float d[3], float tmin, float tmax)
{
    r->org_x = o[0];
    r->org_y = o[1];
    r->org_z = o[2];
    r->dir_x = d[0];
    r->dir_y = d[1];
    r->dir_z = d[2];
    r->tnear = tmin;
    r->tfar = tmax;
    r->time = 0.0f;
    r->mask = 0xffffffffu;
    r->id = 0;
    r->flags = 0;
}

static int fast_intersect(void *ctx, const float o[3], const float d[3], float tmin, float tmax,
                          bvh_hit *h)
{
    struct RTCIntersectContext ic;
    struct RTCRayHit rh;
    rtcInitIntersectContext(&ic);
    fast_ray(&rh.ray, o, d, tmin, tmax);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(((fast *)ctx)->scene, &ic, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return 0;
    h->t = rh.ray.tfar;
    h->prim = (int)rh.hit.primID;
    h->u = rh.hit.u;
    h->v = rh.hit.v;
    return 1;
}

static int fast_occluded(void *ctx, const float o[3], const float d[3], float tmin, float tmax)
{
    struct RTCIntersectContext ic;
    struct RTCRay r;
    rtcInitIntersectContext(&ic);
    fast_ray(&r, o, d, tmin, tmax);
    rtcOccluded1(((fast *)ctx)->scene, &ic, &r);
    return r.tfar < 0.0f; /* Embree's mark of a hit */
}

/* The triangles as one geometry, triangle i as primID i. */
static RTCScene fast_scene(RTCDevice dev, const scene *s)
{
    RTCScene sc = rtcNewScene(dev);
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *v = (float *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                3 * sizeof(float), 3 * (size_t)s->ntris);
    unsigned *ix = (unsigned *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0,
                                                       RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                       (size_t)s->ntris);
    int i, k;
    if (!v || !ix) {
        rtcReleaseGeometry(g);
        rtcReleaseScene(sc);
        return NULL;
    }
    for (i = 0; i < s->ntris; i++)
        for (k = 0; k < 3; k++) {
            v[9 * i + 3 * k + 0] = s->tris[i].v[k][0];
            v[9 * i + 3 * k + 1] = s->tris[i].v[k][1];
            v[9 * i + 3 * k + 2] = s->tris[i].v[k][2];
            ix[3 * i + k] = (unsigned)(3 * i + k);
        }
    rtcCommitGeometry(g);
    rtcAttachGeometry(sc, g);
    rtcReleaseGeometry(g);
    rtcSetSceneFlags(sc, RTC_SCENE_FLAG_ROBUST);
    rtcCommitScene(sc);
    return sc;
}

int bvh_embree(bvh *b, char *err, size_t n)
{
    fast *f = (fast *)calloc(1, sizeof *f);
    if (!f || !(f->dev = rtcNewDevice("threads=1")) ||
        (b->s->ntris > 0 && !(f->scene = fast_scene(f->dev, b->s)))) {
        snprintf(err, n, "Embree: %s", !f ? "out of memory" : "no device or scene");
        if (f)
            fast_release(f);
        return -1;
    }
    if (!f->scene) { /* spheres only */
        fast_release(f);
        return 0;
    }
    b->rays.intersect = fast_intersect;
    b->rays.occluded = fast_occluded;
    b->rays.release = fast_release;
    b->rays.ctx = f;
    return 0;
}
