/* loader.c -- scene files into a scene (scene.h; format in demo/README.md,
 * "Scene files"), and the line reader, errors and material table that
 * obj.c shares.  One pass over each file; the first problem stops the load,
 * is reported as FILE:LINE and leaves *s empty. */
#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "loader_int.h"

int ld_fail(ld_loader *L, const ld_reader *r, int line, const char *fmt, ...)
{
    va_list ap;
    int n;
    if (!L->err || L->errlen == 0)
        return -1;
    n = snprintf(L->err, L->errlen, "%s:%d: ", r->path, line);
    if (n >= 0 && (size_t)n < L->errlen) {
        va_start(ap, fmt);
        vsnprintf(L->err + n, L->errlen - (size_t)n, fmt, ap);
        va_end(ap);
    }
    return -1;
}

/* Doubling, so that n appends cost O(n). */
void *ld_grow(void *p, int *cap, int need, size_t elem)
{
    size_t c = *cap ? (size_t)*cap : 16;
    if (need <= *cap)
        return p;
    while (c < (size_t)need)
        c *= 2;
    if (c > INT_MAX || c > (size_t)-1 / elem || !(p = realloc(p, c * elem)))
        return NULL;
    *cap = (int)c;
    return p;
}

int ld_oom(ld_loader *L, const ld_reader *r)
{
    return ld_fail(L, r, r->line, "out of memory");
}

int ld_read_line(ld_loader *L, ld_reader *r)
{
    int c, n = 0, over = 0;
    char *p;
    while ((c = getc(r->f)) != EOF && c != '\n') {
        if (n <= LD_MAX_LINE)
            r->buf[n++] = (char)c;
        else
            over = 1;
    }
    if (c == EOF && ferror(r->f))
        return ld_fail(L, r, r->line + 1, "read error: %s", strerror(errno));
    if (c == EOF && n == 0)
        return 0;
    r->line++;
    if (n > 0 && r->buf[n - 1] == '\r')
        n--;
    if (over || n > LD_MAX_LINE)
        return ld_fail(L, r, r->line, "line longer than %d characters", LD_MAX_LINE);
    if (memchr(r->buf, '\0', (size_t)n))
        return ld_fail(L, r, r->line, "NUL byte in line");
    r->buf[n] = '\0';
    if ((p = strchr(r->buf, '#')))
        *p = '\0';
    /* split by hand: strtok's hidden state would make loads in two
     * threads interfere */
    r->ntok = 0;
    for (p = r->buf; *p;) {
        p += strspn(p, LD_SEP);
        if (!*p)
            break;
        r->tok[r->ntok++] = p;
        p += strcspn(p, LD_SEP);
        if (*p)
            *p++ = '\0';
    }
    return 1;
}

int ld_nargs(ld_loader *L, const ld_reader *r, int lo, int hi)
{
    int n = r->ntok - 1;
    if (n >= lo && n <= hi)
        return 0;
    if (lo == hi)
        return ld_fail(L, r, r->line, "%s: expected %d argument%s, got %d", r->tok[0], lo,
                       lo == 1 ? "" : "s", n);
    return ld_fail(L, r, r->line, "%s: expected %d to %d arguments, got %d", r->tok[0], lo, hi, n);
}

int ld_nums(ld_loader *L, const ld_reader *r, int first, int n, float *out)
{
    int i;
    for (i = 0; i < n; i++) {
        const char *t = r->tok[first + i];
        char *end;
        double d = strtod(t, &end);
        if (end == t || *end || !isfinite(d) || fabs(d) > FLT_MAX)
            return ld_fail(L, r, r->line, "%s: bad number \"%s\"", r->tok[0], t);
        out[i] = (float)d;
    }
    return 0;
}

int ld_nonneg(ld_loader *L, const ld_reader *r, const float *x, int n)
{
    int i;
    for (i = 0; i < n; i++)
        if (x[i] < 0.0f)
            return ld_fail(L, r, r->line, "%s: negative value %g", r->tok[0], (double)x[i]);
    return 0;
}

int ld_open_file(ld_reader *r, const char *path)
{
    r->path = path;
    r->line = r->ntok = 0;
    r->f = fopen(path, "rb");
    return r->f ? 0 : -1;
}

/* name relative to the directory of the file `from` (absolute names as
 * they are).  Returns a malloc'd path or NULL. */
char *ld_relative_path(const char *from, const char *name)
{
    const char *slash = strrchr(from, '/');
    size_t d = (name[0] == '/' || !slash) ? 0 : (size_t)(slash - from) + 1;
    char *p = malloc(d + strlen(name) + 1);
    if (p) {
        memcpy(p, from, d);
        strcpy(p + d, name);
    }
    return p;
}

/* Opens the file `name` named at the current line of `from`. */
int ld_open_named(ld_loader *L, const ld_reader *from, const char *name, ld_reader *r)
{
    char *path = ld_relative_path(from->path, name);
    int e;
    if (!path)
        return ld_oom(L, from);
    if (ld_open_file(r, path) == 0)
        return 0;
    e = errno;
    free(path);
    return ld_fail(L, from, from->line, "cannot open \"%s\": %s", name, strerror(e));
}

void ld_close_file(ld_reader *r)
{
    if (r->f)
        fclose(r->f);
    r->f = NULL;
}

int ld_find_mat(const scene *s, const char *name)
{
    int i;
    for (i = 0; i < s->nmats; i++)
        if (strcmp(s->mats[i].name, name) == 0)
            return i;
    return -1;
}

int ld_add_mat(ld_loader *L, const ld_reader *r, const char *name)
{
    scene *s = L->s;
    material *m;
    if (strlen(name) >= sizeof s->mats->name)
        return ld_fail(L, r, r->line, "material name longer than %d characters",
                       (int)sizeof s->mats->name - 1);
    if (ld_find_mat(s, name) >= 0)
        return ld_fail(L, r, r->line, "material \"%s\" defined twice", name);
    if (!(m = ld_grow(s->mats, &L->cap_mats, s->nmats + 1, sizeof *m)))
        return ld_oom(L, r);
    s->mats = m;
    m += s->nmats;
    memset(m, 0, sizeof *m);
    strcpy(m->name, name);
    m->kd[0] = m->kd[1] = m->kd[2] = 0.5f;
    m->ns = 1.0f;
    return s->nmats++;
}

/* A material a sphere or usemtl names: defined by an earlier mtllib. */
int ld_use_mat(ld_loader *L, const ld_reader *r, const char *name)
{
    int m = ld_find_mat(L->s, name);
    if (m < 0)
        return ld_fail(L, r, r->line, "material \"%s\" is not defined (by an earlier mtllib)",
                       name);
    return m;
}

static float dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* camera EX EY EZ  LX LY LZ  UX UY UZ  FOV */
static int scene_camera(ld_loader *L, const ld_reader *r)
{
    camera *c = &L->s->cam;
    float x[10], d[3], cr[3];
    int i;
    if (ld_nargs(L, r, 10, 10) < 0 || ld_nums(L, r, 1, 10, x) < 0)
        return -1;
    memcpy(c->eye, x, sizeof c->eye);
    memcpy(c->look, x + 3, sizeof c->look);
    memcpy(c->up, x + 6, sizeof c->up);
    c->fov_deg = x[9];
    if (!(c->fov_deg > 0.0f && c->fov_deg < 180.0f))
        return ld_fail(L, r, r->line, "camera: field of view %g not in (0, 180) degrees",
                       (double)c->fov_deg);
    for (i = 0; i < 3; i++)
        d[i] = c->look[i] - c->eye[i];
    cr[0] = d[1] * c->up[2] - d[2] * c->up[1];
    cr[1] = d[2] * c->up[0] - d[0] * c->up[2];
    cr[2] = d[0] * c->up[1] - d[1] * c->up[0];
    if (dot3(d, d) == 0.0f)
        return ld_fail(L, r, r->line, "camera: the point looked at is the eye");
    /* relative test: the scene's units are arbitrary */
    if (!(dot3(cr, cr) > 1e-12f * dot3(d, d) * dot3(c->up, c->up)))
        return ld_fail(L, r, r->line, "camera: up is parallel to the view direction");
    return 0;
}

static int scene_resolution(ld_loader *L, const ld_reader *r)
{
    long v[2];
    int i;
    if (ld_nargs(L, r, 2, 2) < 0)
        return -1;
    for (i = 0; i < 2; i++) {
        const char *t = r->tok[i + 1];
        char *end;
        errno = 0;
        v[i] = strtol(t, &end, 10);
        if (end == t || *end || errno == ERANGE)
            return ld_fail(L, r, r->line, "resolution: bad integer \"%s\"", t);
        if (v[i] < 1 || v[i] > 16384)
            return ld_fail(L, r, r->line, "resolution: %ld not in 1..16384", v[i]);
    }
    L->s->cam.width = (int)v[0];
    L->s->cam.height = (int)v[1];
    return 0;
}

/* environment constant R G B | gaussian BR BG BB PR PG PB DX DY DZ SIGMA */
static int scene_environment(ld_loader *L, const ld_reader *r)
{
    environment *e = &L->s->env;
    float x[10], len;
    int gauss = r->ntok > 1 && strcmp(r->tok[1], "gaussian") == 0;
    if (r->ntok < 2 || (!gauss && strcmp(r->tok[1], "constant")))
        return ld_fail(L, r, r->line, "environment: expected \"constant\" or \"gaussian\"");
    if (ld_nargs(L, r, gauss ? 11 : 4, gauss ? 11 : 4) < 0 ||
        ld_nums(L, r, 2, r->ntok - 2, x) < 0 || ld_nonneg(L, r, x, gauss ? 6 : 3) < 0)
        return -1;
    memset(e, 0, sizeof *e);
    e->kind = gauss ? ENV_GAUSSIAN : ENV_CONSTANT;
    memcpy(e->base, x, sizeof e->base);
    if (!gauss)
        return 0;
    memcpy(e->peak, x + 3, sizeof e->peak);
    len = sqrtf(dot3(x + 6, x + 6));
    if (!(len > 0.0f) || !isfinite(len))
        return ld_fail(L, r, r->line, "environment: the direction must be a non-zero vector");
    e->dir[0] = x[6] / len;
    e->dir[1] = x[7] / len;
    e->dir[2] = x[8] / len;
    e->sigma_deg = x[9];
    if (!(e->sigma_deg > 0.0f))
        return ld_fail(L, r, r->line, "environment: sigma must be positive");
    return 0;
}

/* sun DX DY DZ R G B: toward the light, and its irradiance */
static int scene_sun(ld_loader *L, const ld_reader *r)
{
    sun *u = &L->s->sun;
    float x[6], len;
    if (ld_nargs(L, r, 6, 6) < 0 || ld_nums(L, r, 1, 6, x) < 0 || ld_nonneg(L, r, x + 3, 3) < 0)
        return -1;
    len = sqrtf(dot3(x, x));
    if (!(len > 0.0f) || !isfinite(len))
        return ld_fail(L, r, r->line, "sun: the direction must be a non-zero vector");
    u->on = 1;
    u->dir[0] = x[0] / len;
    u->dir[1] = x[1] / len;
    u->dir[2] = x[2] / len;
    memcpy(u->e, x + 3, sizeof u->e);
    return 0;
}

/* obj FILE [S TX TY TZ]: the file's vertices scaled by S > 0 about the
 * origin, then moved by T (a model placed in a scene made elsewhere);
 * normals are unchanged by a uniform scale. */
static int scene_obj(ld_loader *L, const ld_reader *r)
{
    scene *s = L->s;
    const int first = s->ntris;
    float x[4];
    int i, k, c;
    if (ld_nargs(L, r, 1, 5) < 0)
        return -1;
    if (r->ntok != 2 && r->ntok != 6)
        return ld_fail(L, r, r->line, "obj: expected a file, or a file, a scale and a move");
    if (r->ntok == 6) {
        if (ld_nums(L, r, 2, 4, x) < 0)
            return -1;
        if (!(x[0] > 0.0f))
            return ld_fail(L, r, r->line, "obj: scale %g must be positive", (double)x[0]);
    }
    if (ld_load_obj(L, r, r->tok[1]) < 0)
        return -1;
    for (i = first; i < s->ntris && r->ntok == 6; i++)
        for (k = 0; k < 3; k++)
            for (c = 0; c < 3; c++) {
                float v = x[0] * s->tris[i].v[k][c] + x[1 + c];
                if (!isfinite(v))
                    return ld_fail(L, r, r->line, "obj: a moved vertex is not finite");
                s->tris[i].v[k][c] = v;
            }
    return 0;
}

/* sphere CX CY CZ R MATERIAL */
static int scene_sphere(ld_loader *L, const ld_reader *r)
{
    scene *s = L->s;
    sphere *sp;
    float x[4];
    int m;
    if (ld_nargs(L, r, 5, 5) < 0 || ld_nums(L, r, 1, 4, x) < 0)
        return -1;
    if (!(x[3] > 0.0f))
        return ld_fail(L, r, r->line, "sphere: radius %g must be positive", (double)x[3]);
    if ((m = ld_use_mat(L, r, r->tok[5])) < 0)
        return -1;
    if (!(sp = ld_grow(s->spheres, &L->cap_spheres, s->nspheres + 1, sizeof *sp)))
        return ld_oom(L, r);
    s->spheres = sp;
    sp += s->nspheres++;
    memcpy(sp->c, x, sizeof sp->c);
    sp->r = x[3];
    sp->mat = m;
    return 0;
}

/* Statements that may appear once: a second one is more likely a mistake
 * than an intended override. */
static int once(ld_loader *L, const ld_reader *r, int *seen)
{
    if (*seen)
        return ld_fail(L, r, r->line, "%s given twice", r->tok[0]);
    *seen = 1;
    return 0;
}

static int scene_statement(ld_loader *L, const ld_reader *r)
{
    const char *k = r->tok[0];
    if (strcmp(k, "mtllib") == 0)
        return ld_nargs(L, r, 1, 1) < 0 ? -1 : ld_load_mtl(L, r, r->tok[1]);
    if (strcmp(k, "obj") == 0)
        return scene_obj(L, r);
    if (strcmp(k, "sun") == 0)
        return once(L, r, &L->have_sun) < 0 ? -1 : scene_sun(L, r);
    if (strcmp(k, "sphere") == 0)
        return scene_sphere(L, r);
    if (strcmp(k, "camera") == 0)
        return once(L, r, &L->have_cam) < 0 ? -1 : scene_camera(L, r);
    if (strcmp(k, "resolution") == 0)
        return once(L, r, &L->have_res) < 0 ? -1 : scene_resolution(L, r);
    if (strcmp(k, "environment") == 0)
        return once(L, r, &L->have_env) < 0 ? -1 : scene_environment(L, r);
    return ld_fail(L, r, r->line, "unknown scene statement \"%s\"", k);
}

static int load_scene(ld_loader *L, const char *path)
{
    ld_reader r;
    int rc;
    if (ld_open_file(&r, path) < 0) {
        /* no file names this one: line 0 stands for the file as a whole */
        ld_fail(L, &r, 0, "cannot open \"%s\": %s", path, strerror(errno));
        return -1;
    }
    while ((rc = ld_read_line(L, &r)) > 0)
        if (r.ntok > 0 && scene_statement(L, &r) < 0) {
            rc = -1;
            break;
        }
    ld_close_file(&r);
    if (rc < 0)
        return -1;
    if (!L->have_cam || !L->have_res)
        return ld_fail(L, &r, r.line > 0 ? r.line : 1, "missing %s statement",
                       !L->have_cam ? "camera" : "resolution");
    return 0;
}

int scene_load(const char *path, scene *s, char *err, size_t errlen)
{
    ld_loader L;
    int i, rc;
    memset(s, 0, sizeof *s);
    memset(&L, 0, sizeof L);
    L.s = s;
    L.err = err;
    L.errlen = errlen;
    if (err && errlen)
        err[0] = '\0';
    rc = load_scene(&L, path);
    for (i = 0; i < L.nmtls; i++)
        free(L.mtls[i]);
    free(L.mtls);
    if (rc < 0)
        scene_free(s);
    return rc;
}

void scene_free(scene *s)
{
    free(s->tris);
    free(s->spheres);
    free(s->mats);
    memset(s, 0, sizeof *s);
}
