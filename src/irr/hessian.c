/*
 * hessian.c -- the occlusion-aware Hessian of irradiance from the samples
 * a record already cast (Schwarzhaupt, Jensen and Jarosz 2012; the
 * per-edge closed forms as Radiance's ambcomp.c evaluates them), and the
 * eigen-decomposition of its tangent-plane part.
 *
 * The hit points of neighbouring strata span triangles; each triangle
 * shines with the radiance of its farthest vertex (a triangle across a
 * silhouette belongs to what lies behind), so E(x) ~ sum_T L_T F_T(x), and
 * the Hessian is sum_T L_T H F_T(x).  A triangle's form factor is the sum
 * over its edges of (n.c) I1/(2 pi) (Lambert's formula, c = r0 x r1), whose
 * second derivatives in x have the closed forms below.  No ray is cast.
 */
#include "../block/form.h"
#include "../sample/sampler.h"
#include "../sample/strata.h"
#include "estimator.h"

#ifndef IRC_NO_HESSIAN

/* Escaped rays get a hit point this many times the record's farthest hit
 * away: far enough that their triangles' derivatives vanish, finite so
 * that the edges along a silhouette against the sky are formed. */
#define IRC__FAR 1e3f
/* Black occluders: every triangle's radiance is lifted by this fraction of
 * the record's mean radiance, so a black blocker against a black wall
 * still bends E (Radiance's ambcomp.c adds 1%). */
#define IRC__FLOOR 0.01f

/* A row of vertices (one row of strata), field by field, each field a row
 * of irc__hstride(N) floats (estimator.h): the hit point relative to x
 * (each vertex starts and ends three edges: per vertex, not per edge), its
 * depth and its sample's radiance. */
enum { IRC__VX, IRC__VY, IRC__VZ, IRC__VDEP, IRC__VL, IRC__VFIELDS = IRC__VL + 3 };
/* (C99 has no static_assert: a negative array size stops the build) */
typedef char irc__hess_fields[IRC__VFIELDS == IRC__HESS_FIELDS ? 1 : -1];

/* A block of four edges' quantities, lane by lane: e = r1 - r0, c = r0 x
 * r1 (its squared length cc), e.e, r0.r1, n.c, I1, |r0|^2, |r1|^2, and
 * whether the edge counts and is too wide for I1's series. */
typedef struct irc__hess_blk {
    float ex[4], ey[4], ez[4], cc[4], ee[4], cs[4], nc[4], i1[4], d0[4], d1[4];
    int ok[4], wide[4];
    int any, anywide;       /* some lane counts; some counts and is wide */
} irc__hess_blk;

/* A block's geometry and I1 from four lanes of the vertex rows v0, v1
 * (stride st), and its weights la - lb into w (three rows of four). */
static void irc__hess_geom(const float *restrict v0, const float *restrict v1,
                           const float *restrict la, const float *restrict lb, uint32_t st,
                           const float nn[3], float *restrict w, irc__hess_blk *restrict b)
{
    const float *x0 = v0, *y0 = x0 + st, *z0 = y0 + st, *x1 = v1, *y1 = x1 + st, *z1 = y1 + st;
    const float *a0 = la, *a1 = a0 + st, *a2 = a1 + st, *b0 = lb, *b1 = b0 + st, *b2 = b1 + st;
    int q, any = 0, anywide = 0;
    for (q = 0; q < 4; q++) {
        w[q] = a0[q] - b0[q];
        w[4 + q] = a1[q] - b1[q];
        w[8 + q] = a2[q] - b2[q];
    }
    for (q = 0; q < 4; q++) {
        const float cx = y0[q] * z1[q] - z0[q] * y1[q], cy = z0[q] * x1[q] - x0[q] * z1[q],
                    cz = x0[q] * y1[q] - y0[q] * x1[q];
        float x2, ics;
        b->ex[q] = x1[q] - x0[q];
        b->ey[q] = y1[q] - y0[q];
        b->ez[q] = z1[q] - z0[q];
        b->d0[q] = x0[q] * x0[q] + y0[q] * y0[q] + z0[q] * z0[q];
        b->d1[q] = x1[q] * x1[q] + y1[q] * y1[q] + z1[q] * z1[q];
        b->cc[q] = cx * cx + cy * cy + cz * cz;
        b->ee[q] = b->ex[q] * b->ex[q] + b->ey[q] * b->ey[q] + b->ez[q] * b->ez[q];
        b->cs[q] = x0[q] * x1[q] + y0[q] * y1[q] + z0[q] * z1[q];
        b->nc[q] = nn[0] * cx + nn[1] * cy + nn[2] * cz;
        /* Degenerate edges (a point, or collinear with x) carry no form
         * factor, edges inside a region of one radiance none that counts. */
        b->ok[q] = (b->cc[q] > 1e-24f * b->d0[q] * b->d1[q]) & (b->ee[q] > 0.0f) &
                   ((w[q] != 0.0f) | (w[4 + q] != 0.0f) | (w[8 + q] != 0.0f));
        /* I1 = angle(r0, r1)/|c| = atan(x)/(x r0.r1), x = |c|/(r0.r1): the
         * grid's edges span a few degrees, where the series in x^2 is exact
         * to 5e-9 (x < 1/4) and needs no square root or arc function;
         * wider ones take atan2 (irc__hess_terms), which stays accurate
         * where acos of the cosine loses half its digits. */
        b->wide[q] = ((b->cs[q] > 0.0f) & (b->cc[q] < 0.0625f * b->cs[q] * b->cs[q])) == 0;
        ics = 1.0f / b->cs[q];
        x2 = b->cc[q] * ics * ics;
        b->i1[q] = (1.0f - x2 * (1.0f / 3 - x2 * (1.0f / 5 - x2 * (1.0f / 7 - x2 * (1.0f / 9 -
                    x2 * (1.0f / 11)))))) * ics;
        any |= b->ok[q];
        anywide |= b->ok[q] & b->wide[q];
    }
    b->any = any;
    b->anywide = anywide;
}

/* A block's six terms of pi H F_e into f (six rows of four), 0 where the
 * edge carries nothing: the closed forms of Schwarzhaupt et al. 2012, the
 * terms I2, J2, I3, J3, K3 as Radiance's ambcomp.c names and evaluates
 * them, with 1/cc and 1/ee taken once. */
static void irc__hess_block(const float *restrict v0, const float *restrict v1, uint32_t st,
                            const float nn[3], const irc__hess_blk *restrict b,
                            float *restrict f)
{
    const float *x0 = v0, *y0 = x0 + st, *z0 = y0 + st, *x1 = v1, *y1 = x1 + st, *z1 = y1 + st;
    const float n0 = nn[0], n1 = nn[1], n2 = nn[2];
    float ft[6][4];
    int q;
    for (q = 0; q < 4; q++) {
        const float ex = b->ex[q], ey = b->ey[q], ez = b->ez[q], ee = b->ee[q], nc = b->nc[q];
        const float er0 = ex * x0[q] + ey * y0[q] + ez * z0[q],
                    er1 = ex * x1[q] + ey * y1[q] + ez * z1[q];
        const float ic = 1.0f / b->cc[q], ie = 1.0f / ee, q0 = 1.0f / b->d0[q],
                    q1 = 1.0f / b->d1[q], u0 = q0 * q0, u1 = q1 * q1; /* 1/|r|^2, ^4 */
        const float i2 = (er1 * q1 - er0 * q0 + ee * b->i1[q]) * (0.5f * ic);
        const float j2 = (0.5f * (q0 - q1) - er0 * i2) * ie;
        const float i3 = (er1 * u1 - er0 * u0 + 3.0f * ee * i2) * (0.25f * ic);
        const float j3 = (0.25f * (u0 - u1) - er0 * i3) * ie;
        const float k3 = (i2 - b->d0[q] * i3 - 2.0f * er0 * j3) * ie;
        /* pi H F_e = (n x e) g^T + g (n x e)^T + (n.c)(4 M - I2 Id), g = I2
         * r0 + J2 e, M = I3 r0 r0^T + J3 (r0 e^T + e r0^T) + K3 e e^T,
         * gathered as r0 P^T + P r0^T + e Q^T + Q e^T - (n.c) I2 Id */
        const float ta = 2.0f * nc * i3, tb = 4.0f * nc * j3, tc = 2.0f * nc * k3;
        const float nx = n1 * ez - n2 * ey, ny = n2 * ex - n0 * ez, nz = n0 * ey - n1 * ex;
        const float px = ta * x0[q] + tb * ex + i2 * nx, py = ta * y0[q] + tb * ey + i2 * ny,
                    pz = ta * z0[q] + tb * ez + i2 * nz;
        const float qx = tc * ex + j2 * nx, qy = tc * ey + j2 * ny, qz = tc * ez + j2 * nz;
        const float di = nc * i2;
        ft[0][q] = 2.0f * (x0[q] * px + ex * qx) - di;
        ft[1][q] = x0[q] * py + px * y0[q] + ex * qy + qx * ey;
        ft[2][q] = x0[q] * pz + px * z0[q] + ex * qz + qx * ez;
        ft[3][q] = 2.0f * (y0[q] * py + ey * qy) - di;
        ft[4][q] = y0[q] * pz + py * z0[q] + ey * qz + qy * ez;
        ft[5][q] = 2.0f * (z0[q] * pz + ez * qz) - di;
    }
    /* a select, not a product: a skipped edge's terms may be inf */
    for (q = 0; q < 4; q++) {
        const int ok = b->ok[q];
        f[q] = ok ? ft[0][q] : 0.0f;
        f[4 + q] = ok ? ft[1][q] : 0.0f;
        f[8 + q] = ok ? ft[2][q] : 0.0f;
        f[12 + q] = ok ? ft[3][q] : 0.0f;
        f[16 + q] = ok ? ft[4][q] : 0.0f;
        f[20 + q] = ok ? ft[5][q] : 0.0f;
    }
}

/* Edges r0 -> r1 of one family (irc__hess_family), `count` of them from
 * the column v0 and v1 point at (IRC__V* rows of stride st), la and lb at
 * the radiances of the triangles that have the edge in this orientation
 * and reversed (three rows).  Into fw, block by block of four lanes (which
 * compilers turn into vector operations), each edge's six terms of pi H
 * F_e and its three weights la - lb. */
static void irc__hess_terms(const float *v0, const float *v1, const float *la, const float *lb,
                            float *fw, uint32_t count, uint32_t st, const float nn[3])
{
    uint32_t k;
    int q;
    for (k = 0; k < count; k += 4) {
        irc__hess_blk b;
        irc__hess_geom(v0 + k, v1 + k, la + k, lb + k, st, nn, fw + 9u * k + 24u, &b);
        if (!b.any) { /* a region of one radiance, as the old scalar loop skipped */
            for (q = 0; q < 24; q++)
                fw[9u * k + (uint32_t)q] = 0.0f;
            continue;
        }
        if (b.anywide)
            for (q = 0; q < 4; q++) /* rare: outside the vector loop */
                if (b.wide[q])
                    b.i1[q] = b.ok[q] ? IRC_ATAN2F(IRC_SQRTF(b.cc[q]), b.cs[q]) /
                                            IRC_SQRTF(b.cc[q])
                                      : 0.0f;
        irc__hess_block(v0 + k, v1 + k, st, nn, &b, fw + 9u * k);
    }
}

/* h[ch][i] -= the sum over a chunk's edges of w_ch f_i, a channel at a
 * time (six sums of four lanes, the weights and the terms fit in a 4-wide
 * target's registers), the lanes added at the chunk's end: the closed
 * forms give -H F_e (Radiance's comp_hessian returns the same sign). */
static void irc__hess_sum(const float *restrict fw, uint32_t count, float h[3][6])
{
    uint32_t k;
    int q, ch;
    for (ch = 0; ch < 3; ch++) {
        float s0[4] = {0, 0, 0, 0}, s1[4] = {0, 0, 0, 0}, s2[4] = {0, 0, 0, 0},
              s3[4] = {0, 0, 0, 0}, s4[4] = {0, 0, 0, 0}, s5[4] = {0, 0, 0, 0};
        for (k = 0; k < count; k += 4) {
            const float *f = fw + 9u * k, *w = f + 24 + 4 * ch;
            for (q = 0; q < 4; q++) {
                s0[q] += w[q] * f[q];
                s1[q] += w[q] * f[4 + q];
                s2[q] += w[q] * f[8 + q];
                s3[q] += w[q] * f[12 + q];
                s4[q] += w[q] * f[16 + q];
                s5[q] += w[q] * f[20 + q];
            }
        }
        h[ch][0] -= (s0[0] + s0[1]) + (s0[2] + s0[3]);
        h[ch][1] -= (s1[0] + s1[1]) + (s1[2] + s1[3]);
        h[ch][2] -= (s2[0] + s2[1]) + (s2[2] + s2[3]);
        h[ch][3] -= (s3[0] + s3[1]) + (s3[2] + s3[3]);
        h[ch][4] -= (s4[0] + s4[1]) + (s4[2] + s4[3]);
        h[ch][5] -= (s5[0] + s5[1]) + (s5[2] + s5[3]);
    }
}

/* The grid the vertices come from. */
typedef struct irc__mesh {
    const irc__sample *s;
    const float *dirs, *nrm;
    const float *n3;        /* the record's normal */
    uint32_t m, n, st;
    int gaps;               /* some stratum escaped or failed */
    float far, fill, floor_l;
} irc__mesh;

/* One family of a row's N edges, one a column (irc__hessian), a chunk of
 * columns at a time into fw and then into h.  The last block's lanes past
 * column N - 1 are copies (finite) and weigh 0. */
static void irc__hess_family(const irc__mesh *g, const float *v0, const float *v1,
                             const float *la, const float *lb, float *fw, float h[3][6])
{
    const uint32_t chunk = irc__hchunk(g->n);
    uint32_t k, c;
    for (k = 0; k < g->n; k += chunk) {
        const uint32_t count = g->n - k < chunk ? (g->n - k + 3u) / 4u * 4u : chunk;
        irc__hess_terms(v0 + k, v1 + k, la + k, lb + k, fw, count, g->st, g->n3);
        for (c = g->n - k; c < count; c++)
            fw[9u * (c & ~3u) + 24u + c % 4u] = fw[9u * (c & ~3u) + 28u + c % 4u] =
                fw[9u * (c & ~3u) + 32u + c % 4u] = 0.0f;
        irc__hess_sum(fw, count, h);
    }
}

static irc__seen irc__hess_seen(const irc__mesh *g, uint32_t i)
{
    return irc__seen_at(g->dirs, g->nrm, i, g->s[i].d);
}

/* A hit beside an escaped stratum lies inside a silhouette, nearer than
 * the silhouette itself when the blocker is curved: its depth is the one
 * strata.c's rule gives from its inner neighbour, across from the escaped
 * one; a polygon's edge keeps its depth. */
static float irc__hess_silhouette(const irc__mesh *g, uint32_t j, uint32_t k, float d)
{
    static const int dj[4] = {0, 0, 1, -1}, dk[4] = {1, -1, 0, 0};
    int q;
    for (q = 0; q < 4; q++) {
        const int64_t out = irc__strata_at(g->m, g->n, (int64_t)j + dj[q], (int64_t)k + dk[q]);
        if (out >= 0 && !(g->s[out].d < HUGE_VALF)) {
            const int64_t in = irc__strata_at(g->m, g->n, (int64_t)j - dj[q], (int64_t)k - dk[q]);
            const irc__seen e = irc__hess_seen(g, j * g->n + k);
            irc__seen inner;
            if (in < 0)
                return d;
            inner = irc__hess_seen(g, (uint32_t)in);
            (void)irc__silhouette_depth(&e, &inner, &d);
            return d;
        }
    }
    return d;
}

/* Row j's vertices into v (IRC__V*).  Escaped strata lie at far, failed
 * ones at the harmonic mean distance; where every ray hit, no hit lies
 * beside a gap (irc__hess_silhouette).  Column N repeats column 0. */
static void irc__hess_row(const irc__mesh *g, uint32_t j, float *restrict v)
{
    const uint32_t n = g->n, st = g->st;
    const irc__sample *s = g->s + j * n;
    const float *dir = g->dirs + 3u * j * n;
    float *x = v, *y = x + st, *z = y + st, *dep = z + st, *l0 = dep + st, *l1 = l0 + st,
          *l2 = l1 + st;
    uint32_t k;
    int f;
    for (k = 0; k < n; k++) {
        float d = s[k].d;
        if (d != d)
            d = g->fill;
        else if (!(d < HUGE_VALF))
            d = g->far;
        else if (g->gaps)
            d = irc__hess_silhouette(g, j, k, d);
        dep[k] = d;
        x[k] = d * dir[3 * k];
        y[k] = d * dir[3 * k + 1];
        z[k] = d * dir[3 * k + 2];
        l0[k] = s[k].l[0];
        l1[k] = s[k].l[1];
        l2[k] = s[k].l[2];
    }
    /* the lanes past column N - 1 read copies: finite, and dropped */
    for (f = 0; f < IRC__VFIELDS; f++)
        for (k = n; k < st; k++)
            v[(uint32_t)f * st + k] = v[(uint32_t)f * st];
}

/* The radiance a triangle of the grid shines with: its farthest vertex's,
 * plus the floor.  Its vertices a, b, c are rows of vertices (IRC__V*)
 * from the first cell's, o three rows of radiances, a cell a column. */
static void irc__hess_shine(const irc__mesh *g, const float *restrict a,
                            const float *restrict b, const float *restrict c, float *restrict o)
{
    const uint32_t st = g->st;
    const float *da = a + IRC__VDEP * st, *db = b + IRC__VDEP * st, *dc = c + IRC__VDEP * st;
    const float fl = g->floor_l;
    uint32_t k;
    int q, ch;
    for (k = 0; k < g->n; k += 4) {
        /* one weight 1 and the others 0: a choice, exact, and no branch */
        const float *xa = da + k, *xb = db + k, *xc = dc + k;
        float pa[4], pb[4], pc[4];
        for (q = 0; q < 4; q++) {
            const int ta = (xa[q] >= xb[q]) & (xa[q] >= xc[q]);
            const int tb = (xb[q] >= xc[q]) & (ta == 0);
            pa[q] = (float)ta;
            pb[q] = (float)tb;
            pc[q] = (float)((ta | tb) ^ 1);
        }
        for (ch = 0; ch < 3; ch++) {
            const float *la = a + (IRC__VL + ch) * st + k, *lb = b + (IRC__VL + ch) * st + k,
                        *lc = c + (IRC__VL + ch) * st + k;
            float *oc = o + ch * st + k;
            for (q = 0; q < 4; q++)
                oc[q] = (pa[q] * la[q] + pb[q] * lb[q] + pc[q] * lc[q]) + fl;
        }
    }
}

/* The Hessian of E at the record, per channel, packed xx xy xz yy yz zz in
 * world space, from the samples and directions of one hemisphere (failed
 * strata carry the mean radiance and the mean hit distance).  Cell (j, k)
 * of the grid, between rows j and j + 1 and columns k and k + 1, holds
 * triangles T1 = (V(j,k), V(j,k+1), V(j+1,k)) and T2 = (V(j+1,k+1),
 * V(j+1,k), V(j,k+1)).  Each grid edge is taken once, with the difference
 * of the radiances of the two triangles that share it (sum_T L_T H F_T
 * sums each edge once with weight la - lb), row by row: row j's edges
 * (j, k) -> (j, k+1), its diagonals (j, k+1) -> (j+1, k) and its
 * verticals (j+1, k) -> (j, k). */
void irc__hessian(const irc_cache *c, const irc__sample *s, const float *dirs,
                  const float n[3], float h[3][6])
{
    const uint32_t m = c->cfg.strata_theta, nphi = c->cfg.strata_phi, st = irc__hstride(nphi);
    float far = 0.0f, mean = 0.0f, inv = 0.0f, *va, *vb, *l1, *l2, *fw, *t;
    uint32_t i, j, hits = 0;
    irc__mesh g;
    IRC_MEMSET(h, 0, 3 * 6 * sizeof(float));
    for (i = 0; i < m * nphi; i++) {
        if (s[i].d == s[i].d && s[i].d < HUGE_VALF) {
            if (s[i].d > far)
                far = s[i].d;
            inv += 1.0f / s[i].d;
            hits++;
        }
        mean += (s[i].l[0] + s[i].l[1] + s[i].l[2]) / 3.0f;
    }
    if (hits == 0 || m < 2 || nphi < 3)
        return;
    g.s = s;
    g.dirs = dirs;
    g.n3 = n;
    g.nrm = irc__slot_normals(c, s);
    g.m = m;
    g.n = nphi;
    g.st = st;
    g.gaps = hits < m * nphi;
    g.fill = hits / inv;
    g.far = far * IRC__FAR;
    g.floor_l = IRC__FLOOR * mean / (m * nphi);
    /* the slot's rows (estimator.h, irc__hscratch_floats): vertices of
     * rows j and j + 1, radiances of the T1s and of the T2s (T2 of cell k
     * in l2[k + 1], cell N - 1's in l2[0]), a chunk of edges */
    va = irc__slot_hess(c, s);
    vb = va + IRC__VFIELDS * st;
    l1 = vb + IRC__VFIELDS * st;
    l2 = l1 + 3u * st;
    fw = l2 + 3u * st;
    IRC_MEMSET(l2, 0, 3u * st * sizeof(float)); /* no row above row 0 */
    irc__hess_row(&g, 0, va);
    for (j = 0; j < m; j++) {
        if (j + 1 < m) {
            irc__hess_row(&g, j + 1, vb);
            irc__hess_shine(&g, va, va + 1, vb, l1);
        } else
            IRC_MEMSET(l1, 0, 3u * st * sizeof(float)); /* no row below */
        /* along the row: T1 of cell k below, T2 of the row above's cell k
         * (l2 still holds the row above's) */
        irc__hess_family(&g, va, va + 1, l1, l2 + 1, fw, h);
        if (j + 1 < m) {
            irc__hess_shine(&g, vb + 1, vb, va + 1, l2 + 1);
            for (i = 0; i < 3; i++)
                l2[i * st] = l2[i * st + nphi];
            /* the diagonal: T1 and T2 of cell k; the vertical: T1 of cell
             * k, T2 of cell k - 1 */
            irc__hess_family(&g, va + 1, vb, l1, l2 + 1, fw, h);
            irc__hess_family(&g, vb, va, l1, l2, fw, h);
        }
        t = va; /* row j + 1 is the next row's top */
        va = vb;
        vb = t;
    }
}

/* Eigen-decomposition of the symmetric 2x2 [[a, b], [b, c]]: l0 >= l1 in
 * |l| and the unit eigenvector (u[0], u[1]) of l0.  The angle comes from
 * atan2 of the signed entries (Radiance's slope from |l| rotates the
 * axes when the smaller eigenvalue is negative). */
void irc__eigen2(float a, float b, float c, float *l0, float *l1, float u[2])
{
    float mid = 0.5f * (a + c), half = 0.5f * (a - c), r = IRC_SQRTF(half * half + b * b);
    float la = mid + r, lb = mid - r, ang = 0.5f * IRC_ATAN2F(2.0f * b, a - c);
    /* ang is the direction of la; swap so that l0 is the larger in size */
    if (IRC_FABSF(lb) > IRC_FABSF(la)) {
        float t = la;
        la = lb;
        lb = t;
        ang += 0.5f * IRC_PI;
    }
    *l0 = la;
    *l1 = lb;
    u[0] = IRC_COSF(ang);
    u[1] = IRC_SINF(ang);
}

#else /* IRC_NO_HESSIAN: the Hessian left out of the build (util.h) */

typedef int irc__no_hessian; /* ISO C wants something in a file */

#endif
