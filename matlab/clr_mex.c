/*
 * clr_mex.c: one MEX gateway from MATLAB/Octave to the clr C ABI (include/clr_contact.h of
 * crates/clr-contact-capi). Build and usage: docs/matlab.md.
 *
 *   F       = clr_mex('normal_force', law, delta, delta_dot, delta_dot_minus)
 *   [F, in] = clr_mex('normal_force', ...)          % in.chi, in.effective_restitution
 *   FT      = clr_mex('friction_force', friction, v_t, f_n)
 *   r       = clr_mex('revolute_forces', joint, law, friction, bearing, journal, impact_velocity)
 *   out     = clr_mex('run_model', toml_text, t_end)
 *   v       = clr_mex('version')
 *
 * law      = {preset_name, c_e}                 e.g. {'LN', 0.5}: flap-paper journal bearing
 *          | {preset_name, c_e, geometry}       geometry: struct with ClrJournalBearing fields
 *          | {elastic, params, damping, c_e}    elastic/damping: CLR_* code or name
 * friction = {kind, params}                     kind: CLR_FRICTION_* code or name; [] = none
 *
 * Every non-OK status of the C ABI raises an error with the identifier "clr:<command>" and the
 * text of clr_last_error_message(); every handle is freed on every path (see fail()).
 */
#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "mex.h"

#include "clr_contact.h"

/* Handles alive during the current call; fail() frees them before raising the error. */
static ClrNormalLaw *g_normal = NULL;
static ClrFrictionLaw *g_friction = NULL;
static ClrRevoluteJoint *g_joint = NULL;
static ClrModel *g_model = NULL;
static char g_msg[4096];
static char g_id[64];

static void free_handles(void)
{
    clr_normal_law_free(g_normal);
    clr_friction_law_free(g_friction);
    clr_revolute_joint_free(g_joint);
    clr_model_free(g_model);
    g_normal = NULL;
    g_friction = NULL;
    g_joint = NULL;
    g_model = NULL;
}

/* Free every handle, then raise "clr:<cmd>" with the message (copied first: it is owned by the
 * library). Does not return. */
static void fail(const char *cmd, const char *msg)
{
    snprintf(g_msg, sizeof g_msg, "%s", msg);
    snprintf(g_id, sizeof g_id, "clr:%s", cmd);
    free_handles();
    mexErrMsgIdAndTxt(g_id, "%s", g_msg);
}

/* Raise the error of a non-OK status. */
static void check(const char *cmd, ClrStatus s)
{
    if (s != CLR_STATUS_OK)
        fail(cmd, clr_last_error_message());
}

/* ---- argument helpers -------------------------------------------------------------------- */

static int is_real_double(const mxArray *a)
{
    return a != NULL && mxIsDouble(a) && !mxIsComplex(a) && !mxIsSparse(a);
}

static double scalar_arg(const char *cmd, const mxArray *a, const char *what)
{
    char buf[256];
    if (!is_real_double(a) || mxGetNumberOfElements(a) != 1) {
        snprintf(buf, sizeof buf, "%s must be a real double scalar", what);
        fail(cmd, buf);
    }
    return mxGetScalar(a);
}

/* A char row vector as a NUL-terminated string in mxMalloc'd memory (freed by MATLAB/Octave at
 * the end of the call if an error is raised). */
static char *string_arg(const char *cmd, const mxArray *a, const char *what)
{
    char buf[256];
    char *s;
    if (a == NULL || !mxIsChar(a)) {
        snprintf(buf, sizeof buf, "%s must be a string (char row vector)", what);
        fail(cmd, buf);
    }
    s = mxArrayToString(a);
    if (s == NULL)
        fail(cmd, "could not convert a string argument");
    return s;
}

/* Code of a kind given as a number or a name (case-insensitive, '_' and ' ' count as '-'). */
static unsigned kind_arg(const char *cmd, const mxArray *a, const char *what,
                         const char *const *names, unsigned n)
{
    char buf[512];
    if (a != NULL && mxIsChar(a)) {
        char *s = string_arg(cmd, a, what);
        unsigned k;
        char *p;
        for (p = s; *p; ++p)
            *p = (*p == '_' || *p == ' ') ? '-' : (char)tolower((unsigned char)*p);
        for (k = 0; k < n; ++k)
            if (strcmp(s, names[k]) == 0) {
                mxFree(s);
                return k;
            }
        snprintf(buf, sizeof buf, "unknown %s `%s`; valid names:", what, s);
        mxFree(s);
        for (k = 0; k < n; ++k) {
            strncat(buf, k ? ", " : " ", sizeof buf - strlen(buf) - 1);
            strncat(buf, names[k], sizeof buf - strlen(buf) - 1);
        }
        fail(cmd, buf);
    }
    {
        double v = scalar_arg(cmd, a, what);
        if (!(v >= 0.0 && v < 4294967296.0) || v != (double)(unsigned)v) {
            snprintf(buf, sizeof buf, "%s must be a non-negative integer code or a name", what);
            fail(cmd, buf);
        }
        return (unsigned)v; /* range checked by the C ABI */
    }
}

/* Names in the order of the CLR_ELASTIC_*, CLR_DAMPING_* and CLR_FRICTION_* codes (the names of
 * crates/clr-contact-capi/src/spec.rs). */
static const char *const ELASTIC_NAMES[] = {
    "hertz",          "power", "linear",           "hertz-sphere-sphere",
    "hertz-sphere-plane", "hertz-internal-cylinder", "liu", "bai-zhao",
    "pereira-internal", "pereira-external", "johnson",
};
static const char *const DAMPING_NAMES[] = {
    "none",   "hunt-crossley",  "lankarani-nikravesh", "flores",
    "gonthier", "zhiying-qishao", "hu-guo",            "gharib-hurmuzlu",
    "herbert-mcwhannell", "lee-wang", "exact",
};
static const char *const FRICTION_NAMES[] = {"coulomb", "ambrosio", "threlfall", "stribeck"};
#define COUNT(a) ((unsigned)(sizeof(a) / sizeof((a)[0])))

/* Optional numeric field of a struct, replacing *v when present. */
static void geometry_field(const char *cmd, const mxArray *s, const char *name, double *v)
{
    const mxArray *f = mxGetField(s, 0, name);
    if (f != NULL)
        *v = scalar_arg(cmd, f, name);
}

/* Build g_normal from a law cell (see the header comment). */
static void build_normal(const char *cmd, const mxArray *law)
{
    size_t n;
    if (law == NULL || !mxIsCell(law))
        fail(cmd, "the normal law must be a cell: {preset_name, c_e}, {preset_name, c_e, "
                  "geometry} or {elastic, params, damping, c_e}");
    n = mxGetNumberOfElements(law);
    if ((n == 2 || n == 3) && mxIsChar(mxGetCell(law, 0))) {
        ClrJournalBearing jb = clr_journal_bearing_flap_paper_test();
        char *name = string_arg(cmd, mxGetCell(law, 0), "the preset name");
        double c_e = scalar_arg(cmd, mxGetCell(law, 1), "c_e");
        ClrStatus s;
        if (n == 3) {
            const mxArray *g = mxGetCell(law, 2);
            if (g == NULL || !mxIsStruct(g) || mxGetNumberOfElements(g) != 1)
                fail(cmd, "the geometry must be a 1x1 struct with fields among "
                          "bearing_youngs_modulus, bearing_poisson_ratio, journal_youngs_modulus, "
                          "journal_poisson_ratio, bearing_radius, journal_radius, length");
            geometry_field(cmd, g, "bearing_youngs_modulus", &jb.bearing_youngs_modulus);
            geometry_field(cmd, g, "bearing_poisson_ratio", &jb.bearing_poisson_ratio);
            geometry_field(cmd, g, "journal_youngs_modulus", &jb.journal_youngs_modulus);
            geometry_field(cmd, g, "journal_poisson_ratio", &jb.journal_poisson_ratio);
            geometry_field(cmd, g, "bearing_radius", &jb.bearing_radius);
            geometry_field(cmd, g, "journal_radius", &jb.journal_radius);
            geometry_field(cmd, g, "length", &jb.length);
        }
        s = clr_normal_law_preset(name, &jb, c_e, &g_normal);
        mxFree(name);
        check(cmd, s);
    } else if (n == 4) {
        unsigned elastic =
            kind_arg(cmd, mxGetCell(law, 0), "elastic kind", ELASTIC_NAMES, COUNT(ELASTIC_NAMES));
        const mxArray *p = mxGetCell(law, 1);
        unsigned damping =
            kind_arg(cmd, mxGetCell(law, 2), "damping kind", DAMPING_NAMES, COUNT(DAMPING_NAMES));
        double c_e = scalar_arg(cmd, mxGetCell(law, 3), "c_e");
        if (p == NULL || !is_real_double(p))
            fail(cmd, "the elastic parameters must be a real double vector");
        check(cmd, clr_normal_law_new(elastic, mxGetPr(p), mxGetNumberOfElements(p), damping, c_e,
                                      &g_normal));
    } else {
        fail(cmd, "the normal law must be a cell: {preset_name, c_e}, {preset_name, c_e, "
                  "geometry} or {elastic, params, damping, c_e}");
    }
}

/* Build g_friction from {kind, params}; [] leaves it NULL (frictionless). */
static void build_friction(const char *cmd, const mxArray *fr)
{
    unsigned kind;
    const mxArray *p;
    if (fr != NULL && mxIsEmpty(fr))
        return;
    if (fr == NULL || !mxIsCell(fr) || mxGetNumberOfElements(fr) != 2)
        fail(cmd, "the friction law must be a cell {kind, params} (or [] for none)");
    kind = kind_arg(cmd, mxGetCell(fr, 0), "friction kind", FRICTION_NAMES, COUNT(FRICTION_NAMES));
    p = mxGetCell(fr, 1);
    if (p == NULL || !is_real_double(p))
        fail(cmd, "the friction parameters must be a real double vector");
    check(cmd, clr_friction_law_new(kind, mxGetPr(p), mxGetNumberOfElements(p), &g_friction));
}

/* Element-wise inputs with scalar expansion: the common element count, and the array whose
 * shape the output takes. */
static size_t common_size(const char *cmd, const mxArray **a, int n, const mxArray **shape)
{
    size_t count = 1;
    int k;
    *shape = a[0];
    for (k = 0; k < n; ++k) {
        size_t m;
        if (!is_real_double(a[k]))
            fail(cmd, "numeric inputs must be real double arrays");
        m = mxGetNumberOfElements(a[k]);
        if (m == 1)
            continue;
        if (count != 1 && m != count)
            fail(cmd, "non-scalar numeric inputs must have the same number of elements");
        count = m;
        *shape = a[k];
    }
    return count;
}

static double at(const mxArray *a, size_t i)
{
    return mxGetNumberOfElements(a) == 1 ? mxGetPr(a)[0] : mxGetPr(a)[i];
}

static mxArray *output_like(const mxArray *shape, size_t count)
{
    if (count == 1)
        return mxCreateDoubleMatrix(1, 1, mxREAL);
    return mxCreateNumericArray(mxGetNumberOfDimensions(shape), mxGetDimensions(shape),
                                mxDOUBLE_CLASS, mxREAL);
}

/* A body state: a 6-vector [x y theta vx vy omega] or a struct with those fields (missing = 0). */
static ClrBodyState body_arg(const char *cmd, const mxArray *a, const char *what)
{
    static const char *const F[6] = {"x", "y", "theta", "vx", "vy", "omega"};
    double v[6] = {0, 0, 0, 0, 0, 0};
    char buf[256];
    ClrBodyState s;
    int k;
    if (a != NULL && mxIsStruct(a) && mxGetNumberOfElements(a) == 1) {
        for (k = 0; k < 6; ++k)
            geometry_field(cmd, a, F[k], &v[k]);
    } else if (is_real_double(a) && mxGetNumberOfElements(a) == 6) {
        for (k = 0; k < 6; ++k)
            v[k] = mxGetPr(a)[k];
    } else {
        snprintf(buf, sizeof buf,
                 "%s must be a 6-vector [x y theta vx vy omega] or a struct with those fields",
                 what);
        fail(cmd, buf);
    }
    s.x = v[0];
    s.y = v[1];
    s.theta = v[2];
    s.vx = v[3];
    s.vy = v[4];
    s.omega = v[5];
    return s;
}

static mxArray *row3(double a, double b, double c)
{
    mxArray *r = mxCreateDoubleMatrix(1, 3, mxREAL);
    mxGetPr(r)[0] = a;
    mxGetPr(r)[1] = b;
    mxGetPr(r)[2] = c;
    return r;
}

/* ---- commands ---------------------------------------------------------------------------- */

static void cmd_normal_force(int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
    const char *cmd = "normal_force";
    const mxArray *shape;
    size_t count, i;
    double *out;
    if (nrhs != 5)
        fail(cmd, "usage: F = clr_mex('normal_force', law, delta, delta_dot, delta_dot_minus)");
    count = common_size(cmd, prhs + 2, 3, &shape);
    build_normal(cmd, prhs[1]);
    plhs[0] = output_like(shape, count);
    out = mxGetPr(plhs[0]);
    for (i = 0; i < count; ++i)
        check(cmd, clr_normal_law_force(g_normal, at(prhs[2], i), at(prhs[3], i), at(prhs[4], i),
                                        &out[i]));
    if (nlhs > 1) {
        static const char *fields[] = {"chi", "effective_restitution"};
        double chi, e;
        check(cmd, clr_normal_law_chi(g_normal, &chi));
        check(cmd, clr_normal_law_effective_restitution(g_normal, &e));
        plhs[1] = mxCreateStructMatrix(1, 1, 2, fields);
        mxSetField(plhs[1], 0, "chi", mxCreateDoubleScalar(chi));
        mxSetField(plhs[1], 0, "effective_restitution", mxCreateDoubleScalar(e));
    }
}

static void cmd_friction_force(int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
    const char *cmd = "friction_force";
    const mxArray *shape;
    size_t count, i;
    double *out;
    (void)nlhs;
    if (nrhs != 4 || mxIsEmpty(prhs[1]))
        fail(cmd, "usage: FT = clr_mex('friction_force', {kind, params}, v_t, f_n)");
    count = common_size(cmd, prhs + 2, 2, &shape);
    build_friction(cmd, prhs[1]);
    plhs[0] = output_like(shape, count);
    out = mxGetPr(plhs[0]);
    for (i = 0; i < count; ++i)
        check(cmd, clr_friction_law_force(g_friction, at(prhs[2], i), at(prhs[3], i), &out[i]));
}

static void cmd_revolute_forces(int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
    static const char *fields[] = {"penetration",     "normal",          "normal_velocity",
                                   "tangential_velocity", "normal_force", "tangential_force",
                                   "bearing",         "journal"};
    const char *cmd = "revolute_forces";
    const mxArray *j;
    double g[6] = {0, 0, 0, 0, 0, 0};
    ClrBodyState bearing, journal;
    ClrRevoluteForces r;
    double v_minus;
    size_t n, k;
    (void)nlhs;
    if (nrhs != 7)
        fail(cmd, "usage: r = clr_mex('revolute_forces', joint, law, friction, bearing, journal, "
                  "impact_velocity)");
    j = prhs[1];
    n = is_real_double(j) ? mxGetNumberOfElements(j) : 0;
    if (n != 2 && n != 6)
        fail(cmd, "joint must be [R_i R_j] or [R_i R_j bx by jx jy] (m)");
    for (k = 0; k < n; ++k)
        g[k] = mxGetPr(j)[k];
    bearing = body_arg(cmd, prhs[4], "bearing");
    journal = body_arg(cmd, prhs[5], "journal");
    v_minus = scalar_arg(cmd, prhs[6], "impact_velocity");
    check(cmd, clr_revolute_joint_new(g[0], g[1], g[2], g[3], g[4], g[5], &g_joint));
    build_normal(cmd, prhs[2]);
    build_friction(cmd, prhs[3]);
    check(cmd, clr_revolute_joint_forces(g_joint, g_normal, g_friction, &bearing, &journal,
                                         v_minus, &r));
    plhs[0] = mxCreateStructMatrix(1, 1, 8, fields);
    mxSetField(plhs[0], 0, "penetration", mxCreateDoubleScalar(r.penetration));
    {
        mxArray *nv = mxCreateDoubleMatrix(1, 2, mxREAL);
        mxGetPr(nv)[0] = r.normal_x;
        mxGetPr(nv)[1] = r.normal_y;
        mxSetField(plhs[0], 0, "normal", nv);
    }
    mxSetField(plhs[0], 0, "normal_velocity", mxCreateDoubleScalar(r.normal_velocity));
    mxSetField(plhs[0], 0, "tangential_velocity", mxCreateDoubleScalar(r.tangential_velocity));
    mxSetField(plhs[0], 0, "normal_force", mxCreateDoubleScalar(r.normal_force));
    mxSetField(plhs[0], 0, "tangential_force", mxCreateDoubleScalar(r.tangential_force));
    mxSetField(plhs[0], 0, "bearing", row3(r.bearing.fx, r.bearing.fy, r.bearing.moment));
    mxSetField(plhs[0], 0, "journal", row3(r.journal.fx, r.journal.fy, r.journal.moment));
}

/* A column or metric name as a MATLAB field name: every character other than a letter, a digit
 * or '_' (the '.' of "rod.theta") becomes '_', a leading non-letter gets an "x" prefix, and the
 * result is cut to 63 characters. */
static void field_name(const char *name, char *out, size_t cap)
{
    size_t i = 0;
    if (!isalpha((unsigned char)name[0]) && i + 1 < cap)
        out[i++] = 'x';
    for (; *name && i + 1 < cap && i < 63; ++name)
        out[i++] = (isalnum((unsigned char)*name) || *name == '_') ? *name : '_';
    out[i] = '\0';
}

static void cmd_run_model(int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
    const char *cmd = "run_model";
    char *text;
    double t_end;
    ClrStatus s;
    uintptr_t n, k;
    uintptr_t impacts = 0;
    mxArray *out, *metrics;
    char fname[80];
    (void)nlhs;
    if (nrhs != 3)
        fail(cmd, "usage: out = clr_mex('run_model', toml_text, t_end)");
    t_end = scalar_arg(cmd, prhs[2], "t_end");
    text = string_arg(cmd, prhs[1], "toml_text");
    s = clr_model_from_toml(text, &g_model);
    mxFree(text);
    check(cmd, s);
    check(cmd, clr_model_run(g_model, t_end));

    out = mxCreateStructMatrix(1, 1, 0, NULL);
    /* Columns (kind 0), one field each. */
    check(cmd, clr_model_name_count(g_model, 0, &n));
    for (k = 0; k < n; ++k) {
        const char *name = NULL;
        const double *ptr = NULL;
        uintptr_t len = 0;
        mxArray *col;
        check(cmd, clr_model_name(g_model, 0, k, &name));
        check(cmd, clr_model_column(g_model, name, &ptr, &len));
        col = mxCreateDoubleMatrix((mwSize)len, 1, mxREAL);
        if (len > 0)
            memcpy(mxGetPr(col), ptr, (size_t)len * sizeof(double));
        field_name(name, fname, sizeof fname);
        mxAddField(out, fname);
        mxSetField(out, 0, fname, col);
    }
    /* Metrics (kind 1), in a sub-struct. */
    metrics = mxCreateStructMatrix(1, 1, 0, NULL);
    check(cmd, clr_model_name_count(g_model, 1, &n));
    for (k = 0; k < n; ++k) {
        const char *name = NULL;
        double v;
        check(cmd, clr_model_name(g_model, 1, k, &name));
        check(cmd, clr_model_metric(g_model, name, &v));
        field_name(name, fname, sizeof fname);
        mxAddField(metrics, fname);
        mxSetField(metrics, 0, fname, mxCreateDoubleScalar(v));
    }
    check(cmd, clr_model_impact_count(g_model, &impacts));
    mxAddField(out, "metrics");
    mxSetField(out, 0, "metrics", metrics);
    mxAddField(out, "impact_count");
    mxSetField(out, 0, "impact_count", mxCreateDoubleScalar((double)impacts));
    free_handles();
    plhs[0] = out;
}

void mexFunction(int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
    char command[64];
    free_handles(); /* all NULL here; defensive */
    if (nrhs < 1 || !mxIsChar(prhs[0]) ||
        mxGetString(prhs[0], command, sizeof command) != 0)
        mexErrMsgIdAndTxt("clr:usage", "usage: clr_mex(command, ...) with command one of "
                                       "'normal_force', 'friction_force', 'revolute_forces', "
                                       "'run_model', 'version'");
    if (strcmp(command, "normal_force") == 0)
        cmd_normal_force(nlhs, plhs, nrhs, prhs);
    else if (strcmp(command, "friction_force") == 0)
        cmd_friction_force(nlhs, plhs, nrhs, prhs);
    else if (strcmp(command, "revolute_forces") == 0)
        cmd_revolute_forces(nlhs, plhs, nrhs, prhs);
    else if (strcmp(command, "run_model") == 0)
        cmd_run_model(nlhs, plhs, nrhs, prhs);
    else if (strcmp(command, "version") == 0)
        plhs[0] = mxCreateString(clr_version());
    else
        mexErrMsgIdAndTxt("clr:usage", "unknown command `%s`; valid: normal_force, "
                                       "friction_force, revolute_forces, run_model, version",
                          command);
    free_handles();
}
