/*
 * scene.h -- the demo tracer's scene, as the loader builds it and the
 * tracer reads it.  Units are the scene file's; y or z up as the file says
 * (the tracer does not care).
 */
#ifndef DEMO_SCENE_H
#define DEMO_SCENE_H

#include <stddef.h>

typedef struct material {
    char name[64];    /* at most 63 characters (longer names are an error) */
    float kd[3];      /* diffuse reflectance (MTL Kd) */
    float ks[3];      /* Phong glossy reflectance (MTL Ks) */
    float ns;         /* Phong exponent (MTL Ns) */
    float ke[3];      /* emitted radiance, front face only (MTL Ke) */
    float bump;       /* procedural bumps h(p) = A sin(F x) sin(F y) sin(F z):
                         A, 0 = none (MTL "bump A F") */
    float bump_freq;  /* F, radians per unit length */
} material;

typedef struct triangle {
    float v[3][3];    /* vertices, counter-clockwise seen from the front */
    float n[3][3];    /* vertex normals (valid when has_n) */
    int has_n;
    int mat;          /* index into scene.mats */
} triangle;

typedef struct sphere {
    float c[3];
    float r;
    int mat;
} sphere;

typedef struct camera {
    float eye[3], look[3], up[3]; /* look is a point the camera looks at */
    float fov_deg;                /* vertical field of view */
    int width, height;            /* pixels */
} camera;

enum { ENV_NONE, ENV_CONSTANT, ENV_GAUSSIAN };

/* Environment radiance for a direction w (unit):
 *   ENV_CONSTANT: base
 *   ENV_GAUSSIAN: base + peak * exp(-angle(w, dir)^2 / (2 sigma^2)),
 *                 angle in radians, sigma = sigma_deg in radians.  The
 *                 papers' "usual Gaussian variation in lighting". */
typedef struct environment {
    int kind;
    float base[3], peak[3];
    float dir[3];      /* unit */
    float sigma_deg;
} environment;

/* A distant light (the sun): from direction dir (unit, toward the light),
 * irradiance e on a surface facing it; one shadow ray a shading point. */
typedef struct sun {
    int on;
    float dir[3];
    float e[3];
} sun;

typedef struct scene {
    triangle *tris;
    int ntris;
    sphere *spheres;
    int nspheres;
    material *mats;
    int nmats;
    camera cam;
    environment env;
    sun sun;
} scene;

/*
 * Load a scene file (format in demo/README.md, "Scene files").  Returns 0, or -1
 * with err holding "FILE:LINE: message" (FILE the file where the problem is:
 * the scene, an OBJ or an MTL; LINE 1-based, or 0 when the scene file
 * itself cannot be opened).  On failure *s is left empty
 * (nothing to free).  On success free it with scene_free().
 */
int scene_load(const char *path, scene *s, char *err, size_t errlen);
void scene_free(scene *s);

#endif
