/*
 * camera.h -- the pinhole camera's frame and primary rays (shared by the
 * integrator and the records view).
 */
#ifndef DEMO_CAMERA_H
#define DEMO_CAMERA_H

#include "scene.h"
#include "shade.h"

typedef struct cam_frame {
    float eye[3], f[3], right[3], up[3], tx, ty;
} cam_frame;

void camera_frame(const camera *c, cam_frame *cf);
/* The unit direction through pixel (x, y)'s centre. */
void camera_ray(const cam_frame *cf, const camera *c, int x, int y, float d[3]);
/* The same through any point (x, y) of the image plane, in pixels from
 * its top-left corner (a pixel's centre is at + 0.5). */
void camera_ray_at(const cam_frame *cf, const camera *c, float x, float y, float d[3]);
/* The width of pixel (x, y)'s footprint on a surface of normal n hit at
 * distance t along the pixel's direction d: the square root of the area
 * the pixel's cone cuts from the surface's plane (pbrt's sqrt(|dp/dx x
 * dp/dy|)); grazing surfaces count as 1/20 of facing ones at most. */
float camera_footprint(const cam_frame *cf, const camera *c, const float d[3], float t,
                       const float n[3]);
/* The point the cache sees for a surface: lifted off it along the
 * geometric normal so that hemisphere rays start clear of it. */
void cache_point(const surface *sf, float p[3]);

#endif
