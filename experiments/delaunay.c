/*
 * delaunay.c -- the Delaunay triangulation of points on an integer grid
 * inside a rectangle, by Bowyer-Watson insertion (sampling.h).
 *
 * Coordinates are integers of at most 13 bits, so the orientation and
 * in-circle determinants are exact in 64-bit integers (the in-circle's
 * terms reach 2^58): no rounding can make the cavity of an insertion
 * other than star-shaped, whatever the degeneracies (the quad-tree's
 * samples are full of co-circular fours).  A point on the circumcircle
 * is not inside it: ties keep the existing triangles.
 */
#include "sampling.h"

#include <stdlib.h>

typedef struct dtri {
    int v[3];   /* counter-clockwise */
    int nb[3];  /* nb[i]: the triangle across the edge opposite v[i], -1 none */
} dtri;

typedef struct dmesh {
    const long long *xy;
    dtri *t;
    int nt, cap;
    int *mark, stamp;          /* cavity membership by stamp */
    int *cav, ncav;            /* the cavity's triangles */
    int *start, *end;          /* new triangles by the vertex their edge starts / ends at */
    int *ea, *eb, *eo, *made;  /* a cavity's boundary edges (a, b), the
                                  triangle outside each, the new triangles */
    int last;                  /* where the next walk starts */
} dmesh;

static long long orient(const long long *a, const long long *b, const long long *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* > 0 when d lies inside the circle through a, b, c (counter-clockwise). */
static long long incircle(const long long *a, const long long *b, const long long *c,
                          const long long *d)
{
    const long long adx = a[0] - d[0], ady = a[1] - d[1], bdx = b[0] - d[0],
                    bdy = b[1] - d[1], cdx = c[0] - d[0], cdy = c[1] - d[1];
    return (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) +
           (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
           (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
}

static const long long *pt(const dmesh *m, int i)
{
    return m->xy + 2 * (long)i;
}

/* The triangle holding p (inside or on an edge), by a visibility walk from
 * the last one made; -1 if p is outside the rectangle. */
static int locate(const dmesh *m, const long long *p)
{
    int t = m->last, steps = 0;
    while (t >= 0 && steps++ <= m->nt) {
        const dtri *d = &m->t[t];
        int i, next = -2;
        for (i = 0; i < 3 && next == -2; i++)
            if (orient(pt(m, d->v[(i + 1) % 3]), pt(m, d->v[(i + 2) % 3]), p) < 0)
                next = d->nb[i];
        if (next == -2)
            return t;
        t = next;
    }
    return -1;
}

static int in_cavity(const dmesh *m, int t)
{
    return t >= 0 && m->mark[t] == m->stamp;
}

/* The triangles whose circumcircle holds p, from the one holding it. */
static void cavity(dmesh *m, int t0, const long long *p)
{
    int k;
    m->stamp++;
    m->ncav = 0;
    m->cav[m->ncav++] = t0;
    m->mark[t0] = m->stamp;
    for (k = 0; k < m->ncav; k++) {
        const dtri *d = &m->t[m->cav[k]];
        int i;
        for (i = 0; i < 3; i++) {
            const int u = d->nb[i];
            if (u < 0 || in_cavity(m, u))
                continue;
            if (incircle(pt(m, m->t[u].v[0]), pt(m, m->t[u].v[1]), pt(m, m->t[u].v[2]), p) > 0) {
                m->mark[u] = m->stamp;
                m->cav[m->ncav++] = u;
            }
        }
    }
}

/* Makes triangle (a, b, p) across from `outer` in slot s; outer's edge
 * (b, a) is found by its vertices (an outer triangle may border the
 * cavity twice, and slot numbers are being reused). */
static void fan(dmesh *m, int s, int a, int b, int p, int outer)
{
    dtri *d = &m->t[s];
    int i;
    d->v[0] = a;
    d->v[1] = b;
    d->v[2] = p;
    d->nb[0] = d->nb[1] = -1;
    d->nb[2] = outer;
    if (outer >= 0)
        for (i = 0; i < 3; i++)
            if (m->t[outer].v[(i + 1) % 3] == b && m->t[outer].v[(i + 2) % 3] == a)
                m->t[outer].nb[i] = s;
    m->start[a] = s;
    m->end[b] = s;
}

/* Replaces the cavity of point p by the fan of its boundary edges around
 * p; an edge p lies on (a hull edge) gets no triangle.  The cavity's slots
 * are reused first. */
static int refill(dmesh *m, int p)
{
    int k, used = 0, nmade = 0, i, ne = 0;
    int *ea = m->ea, *eb = m->eb, *eo = m->eo, *made = m->made;
    /* The cavity's boundary edges, read before any slot is overwritten. */
    for (k = 0; k < m->ncav; k++) {
        const dtri *d = &m->t[m->cav[k]];
        for (i = 0; i < 3; i++) {
            const int a = d->v[(i + 1) % 3], b = d->v[(i + 2) % 3];
            if (in_cavity(m, d->nb[i]))
                continue;
            if (orient(pt(m, a), pt(m, b), pt(m, p)) == 0) {
                if (d->nb[i] >= 0)
                    return -1; /* only a hull edge can hold p */
                continue;
            }
            if (ne == m->cap + 2)
                return -1;
            ea[ne] = a;
            eb[ne] = b;
            eo[ne] = d->nb[i];
            ne++;
        }
    }
    for (k = 0; k < ne; k++) {
        int s;
        if (used < m->ncav) {
            s = m->cav[used++];
        } else {
            if (m->nt == m->cap)
                return -1;
            s = m->nt++;
        }
        m->mark[s] = 0;
        fan(m, s, ea[k], eb[k], p, eo[k]);
        made[nmade++] = s;
    }
    if (used < m->ncav)
        return -1; /* a cavity yields at least as many triangles as it had */
    for (k = 0; k < nmade; k++) {
        dtri *d = &m->t[made[k]];
        const int nx = m->start[d->v[1]], pv = m->end[d->v[0]];
        d->nb[0] = nx >= 0 && m->t[nx].v[0] == d->v[1] && m->t[nx].v[2] == p ? nx : -1;
        d->nb[1] = pv >= 0 && m->t[pv].v[1] == d->v[0] && m->t[pv].v[2] == p ? pv : -1;
    }
    for (k = 0; k < nmade; k++) {
        m->start[m->t[made[k]].v[0]] = -1;
        m->end[m->t[made[k]].v[1]] = -1;
    }
    m->last = made[0];
    return 0;
}

static int mesh_init(dmesh *m, const long long *xy, int n)
{
    int i;
    m->xy = xy;
    m->cap = 2 * n + 2;
    m->t = malloc(sizeof *m->t * (size_t)m->cap);
    m->mark = calloc((size_t)m->cap, sizeof *m->mark);
    m->cav = malloc(sizeof *m->cav * (size_t)m->cap);
    m->start = malloc(sizeof *m->start * (size_t)n);
    m->end = malloc(sizeof *m->end * (size_t)n);
    m->ea = malloc(sizeof *m->ea * 4 * ((size_t)m->cap + 2));
    m->eb = m->ea ? m->ea + m->cap + 2 : NULL;
    m->eo = m->ea ? m->eb + m->cap + 2 : NULL;
    m->made = m->ea ? m->eo + m->cap + 2 : NULL;
    if (!m->t || !m->mark || !m->cav || !m->start || !m->end || !m->ea)
        return -1;
    for (i = 0; i < n; i++)
        m->start[i] = m->end[i] = -1;
    m->stamp = 0;
    return 0;
}

static void mesh_free(dmesh *m)
{
    free(m->mark);
    free(m->cav);
    free(m->start);
    free(m->end);
    free(m->ea);
}

int delaunay(const long long *xy, int n, int **tri, int *ntri)
{
    dmesh m;
    int i, st = 0, a = 0, b = 1, c = 2, d = 3;
    *tri = NULL;
    *ntri = 0;
    if (n < 4)
        return -1;
    for (i = 0; i < 2 * n; i++)
        if (xy[i] > 8192 || xy[i] < -8192)
            return -1;
    if (mesh_init(&m, xy, n) < 0) {
        free(m.t);
        mesh_free(&m);
        return -1;
    }
    /* The rectangle as two triangles, counter-clockwise. */
    if (orient(pt(&m, 0), pt(&m, 1), pt(&m, 2)) < 0) {
        b = 3;
        d = 1;
    }
    if (orient(pt(&m, a), pt(&m, b), pt(&m, c)) <= 0 ||
        orient(pt(&m, a), pt(&m, c), pt(&m, d)) <= 0) {
        free(m.t);
        mesh_free(&m);
        return -1;
    }
    m.t[0].v[0] = a; m.t[0].v[1] = b; m.t[0].v[2] = c;
    m.t[0].nb[0] = -1; m.t[0].nb[1] = 1; m.t[0].nb[2] = -1;
    m.t[1].v[0] = a; m.t[1].v[1] = c; m.t[1].v[2] = d;
    m.t[1].nb[0] = -1; m.t[1].nb[1] = -1; m.t[1].nb[2] = 0;
    m.nt = 2;
    m.last = 0;
    for (i = 4; i < n && st == 0; i++) {
        const int t0 = locate(&m, pt(&m, i));
        if (t0 < 0) {
            st = -1;
            break;
        }
        cavity(&m, t0, pt(&m, i));
        st = refill(&m, i);
    }
    mesh_free(&m);
    if (st == 0 && (*tri = malloc(sizeof **tri * 3 * (size_t)m.nt)) == NULL)
        st = -1;
    if (st == 0) {
        for (i = 0; i < m.nt; i++) {
            (*tri)[3 * i] = m.t[i].v[0];
            (*tri)[3 * i + 1] = m.t[i].v[1];
            (*tri)[3 * i + 2] = m.t[i].v[2];
        }
        *ntri = m.nt;
    }
    free(m.t);
    return st;
}
