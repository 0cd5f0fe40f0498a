/*
 * glossy.h -- one bounce of glossy indirect light at a camera ray's hit,
 * for the demo's Phong lobe ks (s + 2)/(2 pi) max(0, r.w)^s (shade.c's
 * brdf; r the view's mirror direction about the shading normal): from an
 * SH record, as the SH-gradient paper shades glossy objects from its
 * records' coefficients, or by sampling the lobe with rays, which a host
 * does where the record's bands cannot carry it.
 */
#ifndef DEMO_GLOSSY_H
#define DEMO_GLOSSY_H

#include <stdint.h>

#include "irrcache.h"
#include "shade.h"

/* Whether sf's material has a glossy lobe. */
int glossy_has(const surface *sf);

/* The mirror direction r of the view d (toward the surface) about sf's
 * shading normal; returns r.n (0 when r points into the surface). */
float glossy_axis(const surface *sf, const float d[3], float r[3]);

/* Reflected glossy radiance from sh's record: the lobe times the cosine
 * integrated against the record's band-limited radiance (irc_sh_radiance)
 * over GLOSSY_SH_DIRS stratified samples of the lobe, no ray cast.  (The
 * zonal form, irc_sh_glossy about r with the cosine taken at the axis,
 * leaves broad lobes 30% high at normal incidence and low at grazing
 * angles.)  Returns irc_sh_radiance's status. */
#define GLOSSY_SH_DIRS 64
int glossy_from_sh(const irc_sh *sh, const surface *sf, const float d[3], float out[3]);

/* Sample i of n of the lobe about r (pdf (s + 1)/(2 pi) (r.w)^s,
 * stratified on an m x k grid as the reference's hemisphere rays are):
 * its direction w, and f cos / pdf = ks (s + 2)/(s + 1) (w.n) per
 * channel, 0 when w is below the surface. */
void glossy_sample(const surface *sf, const float r[3], uint64_t key, int i, int n, float w[3],
                   float weight[3]);

#endif
