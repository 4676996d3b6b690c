/*
 * C test of libclr_contact_capi against the unit-test checklist of contact-laws.md §7
 * (steel E = 207 GPa, nu = 0.3). Built and run by tests/c_program.rs with the machine's `cc`.
 *
 * Tolerances: the §7 tables print 7–8 significant digits, so closed-form values are compared with
 * a relative tolerance of 1e-7 (half a unit of the last printed digit or better); values printed
 * with 6 decimals (restitution, chi_exact, moments) with an absolute tolerance of 1e-6.
 * Prints one line per check and "N passed, M failed"; exits non-zero on any failure.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "clr_contact.h"

static int passed = 0;
static int failed = 0;

static void check(const char *what, int ok) {
    if (ok) {
        passed++;
        printf("ok   %s\n", what);
    } else {
        failed++;
        printf("FAIL %s (last error: %s)\n", what, clr_last_error_message());
    }
}

static void close_rel(const char *what, double got, double expected, double rel) {
    int ok = fabs(got - expected) <= rel * fabs(expected);
    if (!ok) printf("     %s: got %.10g, expected %.10g (rel tol %g)\n", what, got, expected, rel);
    check(what, ok);
}

static void close_abs(const char *what, double got, double expected, double tol) {
    int ok = fabs(got - expected) <= tol;
    if (!ok) printf("     %s: got %.10g, expected %.10g (abs tol %g)\n", what, got, expected, tol);
    check(what, ok);
}

static void status_is(const char *what, ClrStatus got, ClrStatus expected) {
    if (got != expected) printf("     %s: status %d, expected %d\n", what, (int)got, (int)expected);
    check(what, got == expected);
}

static const double E = 207e9, NU = 0.3;
static const double RI = 10e-3, RJ = 9.9e-3, L = 15e-3, C = 0.1e-3;

/* Composite modulus E* = 1/(sigma_i + sigma_j), sigma = (1 - nu^2)/E (contact-laws.md §0). */
static double e_star(void) { return 1.0 / (2.0 * (1.0 - NU * NU) / E); }

static ClrNormalLaw *internal_law(ClrDampingKind damping) {
    double p[6] = {E, NU, RI, E, NU, RJ};
    ClrNormalLaw *law = NULL;
    ClrStatus s = clr_normal_law_new(CLR_ELASTIC_HERTZ_INTERNAL_CYLINDER, p, 6, damping, 0.5, &law);
    status_is("create internal-cylinder law", s, CLR_STATUS_OK);
    return law;
}

/* A normal law with a one-parameter elastic part (Hertz K, linear k); `what` names the check. */
static ClrNormalLaw *one_parameter_law(const char *what, ClrElasticKind elastic, double k,
                                       ClrDampingKind damping, double c_e) {
    double p[1] = {k};
    ClrNormalLaw *law = NULL;
    status_is(what, clr_normal_law_new(elastic, p, 1, damping, c_e, &law), CLR_STATUS_OK);
    return law;
}

static double force(const ClrNormalLaw *law, double d, double dd, double ddm) {
    double f = NAN;
    ClrStatus s = clr_normal_law_force(law, d, dd, ddm, &f);
    if (s != CLR_STATUS_OK) printf("     force: status %d: %s\n", (int)s, clr_last_error_message());
    return f;
}

/* §7.1 and §7.2: the dissipative laws on the internal revolute K, delta = 10 um,
 * delta_dot_minus = 0.5 m/s, c_e = 0.5. */
static void normal_laws(void) {
    ClrNormalLaw *ln = internal_law(CLR_DAMPING_LANKARANI_NIKRAVESH);
    double fe = NAN, chi = NAN, e = NAN;
    status_is("elastic force status", clr_normal_law_elastic_force(ln, 10e-6, &fe), CLR_STATUS_OK);
    close_rel("7.1 internal revolute F_e(10 um) = 4771.5040 N", fe, 4771.5040, 1e-7);
    status_is("chi status", clr_normal_law_chi(ln, &chi), CLR_STATUS_OK);
    close_rel("7.2 L-N chi = 0.5625", chi, 0.5625, 1e-12);
    close_rel("7.2 L-N F(+0.25) = 6113.4895 N", force(ln, 10e-6, 0.25, 0.5), 6113.4895, 1e-7);
    close_rel("7.2 L-N F(-0.25) = 3429.5185 N", force(ln, 10e-6, -0.25, 0.5), 3429.5185, 1e-7);
    status_is("restitution status", clr_normal_law_effective_restitution(ln, &e), CLR_STATUS_OK);
    close_abs("7.3 L-N e_eff(c_e = 0.5) = 0.725241", e, 0.725241, 1e-6);
    check("7.2 F = 0 for delta <= 0", force(ln, -1e-6, 0.25, 0.5) == 0.0);

    /* The floor of delta_dot_minus: with a floor of 0.5 m/s, an onset rate of 1e-6 m/s acts as
     * 0.5 m/s, so the §7.2 value comes back. */
    status_is("set floor", clr_normal_law_set_min_impact_velocity(ln, 0.5), CLR_STATUS_OK);
    close_rel("floored delta_dot_minus gives F(+0.25) = 6113.4895 N", force(ln, 10e-6, 0.25, 1e-6),
              6113.4895, 1e-7);
    status_is("floor <= 0 rejected", clr_normal_law_set_min_impact_velocity(ln, 0.0),
              CLR_STATUS_INVALID_PARAMETER);
    clr_normal_law_free(ln);

    ClrNormalLaw *fl = internal_law(CLR_DAMPING_FLORES);
    close_rel("7.2 Flores F(+0.25) = 8588.7072 N", force(fl, 10e-6, 0.25, 0.5), 8588.7072, 1e-7);
    close_rel("7.2 Flores F(-0.25) = 954.3008 N", force(fl, 10e-6, -0.25, 0.5), 954.3008, 1e-7);
    check("7.2 F clamped at 0 when 1 + chi*dd/ddm < 0", force(fl, 10e-6, -0.5, 0.5) == 0.0);
    clr_normal_law_free(fl);

    ClrNormalLaw *zq = internal_law(CLR_DAMPING_ZHIYING_QISHAO);
    close_rel("7.2 Zhiying-Qishao F(+0.25) = 8419.3988 N", force(zq, 10e-6, 0.25, 0.5), 8419.3988,
              1e-7);
    clr_normal_law_free(zq);

    /* Presets of the flap paper on its journal-bearing test geometry (same K as §7.1). */
    ClrJournalBearing jb = clr_journal_bearing_flap_paper_test();
    close_rel("flap test geometry R_i = 10 mm", jb.bearing_radius, RI, 1e-15);
    ClrNormalLaw *p = NULL;
    status_is("preset LN", clr_normal_law_preset("LN", &jb, 0.5, &p), CLR_STATUS_OK);
    close_rel("preset LN F(-0.25) = 3429.5185 N", force(p, 10e-6, -0.25, 0.5), 3429.5185, 1e-7);
    clr_normal_law_free(p);
    p = NULL;
    status_is("preset gonthier", clr_normal_law_preset("gonthier", &jb, 0.5, &p), CLR_STATUS_OK);
    close_rel("preset Gonthier F(+0.25) = 8350.1320 N", force(p, 10e-6, 0.25, 0.5), 8350.1320,
              1e-7);
    clr_normal_law_free(p);

    /* §7.5 cylinder laws with Delta R = 0.1 mm, L = 15 mm. */
    double liu_p[3] = {e_star(), C, L};
    ClrNormalLaw *liu = NULL;
    status_is("create Liu", clr_normal_law_new(CLR_ELASTIC_LIU, liu_p, 3, CLR_DAMPING_NONE, 1.0, &liu),
              CLR_STATUS_OK);
    clr_normal_law_elastic_force(liu, 1e-6, &fe);
    close_rel("7.5 Liu F(1 um) = 188.55342 N", fe, 188.55342, 1e-7);
    clr_normal_law_free(liu);

    double bz_p[2] = {e_star(), C};
    ClrNormalLaw *bz = NULL;
    status_is("create Bai-Zhao",
              clr_normal_law_new(CLR_ELASTIC_BAI_ZHAO, bz_p, 2, CLR_DAMPING_LANKARANI_NIKRAVESH, 0.5,
                                 &bz),
              CLR_STATUS_OK);
    close_rel("7.5 Bai-Zhao hybrid F(10 um, 0.25, 0.5) = 2244.7536 N", force(bz, 10e-6, 0.25, 0.5),
              2244.7536, 1e-7);
    clr_normal_law_free(bz);
}

/* §1.3 and §7.3: damping factors and the exact restitution relation. */
static void restitution(void) {
    double chi = NAN, e = NAN;
    status_is("chi_exact status", clr_damping_chi(CLR_DAMPING_EXACT, 0.5, &chi), CLR_STATUS_OK);
    close_abs("7.3 chi_exact(0.5) = 1.432751", chi, 1.432751, 1e-6);
    clr_damping_chi(CLR_DAMPING_EXACT, 0.9, &chi);
    close_abs("7.3 chi_exact(0.9) = 0.166482", chi, 0.166482, 1e-6);
    clr_damping_chi(CLR_DAMPING_ZHIYING_QISHAO, 0.5, &chi);
    /* 0.75 * 0.75 * e = 1.52903353; the §7.2 table prints it as 1.5290340, i.e. good to 6
     * decimals, hence the absolute tolerance. */
    close_abs("7.2 Zhiying-Qishao chi(0.5) = 1.5290340", chi, 1.5290340, 1e-6);
    status_is("e_eff status", clr_effective_restitution(0.5625, &e), CLR_STATUS_OK);
    close_abs("7.3 e_eff(chi = 0.5625) = 0.725241", e, 0.725241, 1e-6);
    clr_effective_restitution(1.6, &e);
    close_abs("1.3 table: Flores e_eff(c_e = 0.5) = 0.4704", e, 0.4704, 5e-5);
}

/* §7.6 friction, F_N = 1000 N. */
static void friction(void) {
    ClrFrictionLaw *law = NULL;
    double f = NAN, mu = NAN;

    double coulomb[2] = {0.1, 1e-3};
    status_is("create Coulomb", clr_friction_law_new(CLR_FRICTION_COULOMB, coulomb, 2, &law),
              CLR_STATUS_OK);
    clr_friction_law_force(law, 0.02, 1000.0, &f);
    close_rel("7.6 Coulomb F_T(0.02) = -100 N", f, -100.0, 1e-12);
    clr_friction_law_free(law);

    double amb[3] = {0.1, 1e-4, 1e-3};
    clr_friction_law_new(CLR_FRICTION_AMBROSIO, amb, 3, &law);
    clr_friction_law_force(law, 5e-5, 1000.0, &f);
    close_abs("7.6 Ambrosio F_T(5e-5) = 0 N", f, 0.0, 1e-12);
    clr_friction_law_force(law, 5.5e-4, 1000.0, &f);
    close_rel("7.6 Ambrosio F_T(5.5e-4) = -50 N", f, -50.0, 1e-9);
    clr_friction_law_force(law, -5.5e-4, 1000.0, &f);
    close_rel("7.6 Ambrosio F_T(-5.5e-4) = +50 N", f, 50.0, 1e-9);
    clr_friction_law_force(law, 2e-3, 1000.0, &f);
    close_rel("7.6 Ambrosio F_T(2e-3) = -100 N", f, -100.0, 1e-12);
    clr_friction_law_free(law);

    double thr[2] = {0.1, 0.01};
    clr_friction_law_new(CLR_FRICTION_THRELFALL, thr, 2, &law);
    clr_friction_law_force(law, 0.01, 1000.0, &f);
    close_rel("7.6 Threlfall F_T(0.01) = -95.02129 N", f, -95.02129, 1e-7);
    clr_friction_law_force(law, 0.001, 1000.0, &f);
    close_rel("7.6 Threlfall F_T(0.001) = -25.91818 N", f, -25.91818, 1e-7);
    clr_friction_law_free(law);

    double stb[4] = {0.2, 0.1, 0.01, 0.1};
    clr_friction_law_new(CLR_FRICTION_STRIBECK, stb, 4, &law);
    const double v[7] = {0.0, 0.005, -0.005, 0.01, 0.055, 0.1, 0.2};
    const double expected[7] = {0.0, -0.1375, 0.1375, -0.2, -0.15, -0.1, -0.1};
    for (int i = 0; i < 7; i++) {
        char what[96];
        snprintf(what, sizeof what, "7.6 Stribeck mu(%g) = %g", v[i], expected[i]);
        clr_friction_law_coefficient(law, v[i], &mu);
        close_abs(what, mu, expected[i], 1e-12);
    }
    clr_friction_law_free(law);
}

/* §7.7 revolute kinematics and forces: bearing fixed at the origin, journal centre at
 * (c + delta) n with n = (0.6, 0.8), journal velocity (0.3, 0.4) m/s, omega_j = 10 rad/s; L-N
 * (c_e = 0.5, delta_dot_minus = 0.5) and Ambrosio (mu = 0.1, so c_d = 1). */
static void revolute(void) {
    ClrRevoluteJoint *joint = NULL;
    status_is("create joint", clr_revolute_joint_new(RI, RJ, 0.0, 0.0, 0.0, 0.0, &joint),
              CLR_STATUS_OK);
    ClrJournalBearing jb = clr_journal_bearing_flap_paper_test();
    ClrNormalLaw *ln = NULL;
    clr_normal_law_preset("LN", &jb, 0.5, &ln);
    double amb[3] = {0.1, 1e-4, 1e-3};
    ClrFrictionLaw *fr = NULL;
    clr_friction_law_new(CLR_FRICTION_AMBROSIO, amb, 3, &fr);

    const double e = C + 10e-6;
    ClrBodyState bearing = {0};
    ClrBodyState journal = {e * 0.6, e * 0.8, 0.0, 0.3, 0.4, 10.0};
    ClrRevoluteForces out;
    memset(&out, 0, sizeof out);
    status_is("revolute forces status",
              clr_revolute_joint_forces(joint, ln, fr, &bearing, &journal, 0.5, &out), CLR_STATUS_OK);
    close_rel("7.7 penetration = 10 um", out.penetration, 10e-6, 1e-9);
    close_rel("7.7 v_N = 0.5 m/s", out.normal_velocity, 0.5, 1e-12);
    close_rel("7.7 v_T = 0.099 m/s", out.tangential_velocity, 0.099, 1e-12);
    close_rel("7.7 F_N = 7455.4750 N", out.normal_force, 7455.4750, 1e-7);
    close_rel("7.7 F_T = -745.5475 N", out.tangential_force, -745.5475, 1e-7);
    close_rel("7.7 f_j,x = -3876.8470 N", out.journal.fx, -3876.8470, 1e-7);
    close_rel("7.7 f_j,y = -6411.7085 N", out.journal.fy, -6411.7085, 1e-7);
    close_abs("7.7 m_j = -7.380920 N m", out.journal.moment, -7.380920, 1e-6);
    close_rel("7.7 f_i,x = 3876.8470 N", out.bearing.fx, 3876.8470, 1e-7);
    close_rel("7.7 f_i,y = 6411.7085 N", out.bearing.fy, 6411.7085, 1e-7);
    close_abs("7.7 m_i = +7.455475 N m", out.bearing.moment, 7.455475, 1e-6);

    /* Frictionless (NULL friction): only the normal force, no moment on the journal about its
     * centre (the normal force passes through it). */
    clr_revolute_joint_forces(joint, ln, NULL, &bearing, &journal, 0.5, &out);
    close_rel("frictionless f_j,x = -0.6 F_N", out.journal.fx, -0.6 * 7455.4750, 1e-7);
    close_abs("frictionless m_j = 0", out.journal.moment, 0.0, 1e-9);

    /* Out of contact: concentric journal, zero forces. */
    ClrBodyState centred = {0.0, 0.0, 0.0, 0.3, 0.4, 10.0};
    clr_revolute_joint_forces(joint, ln, fr, &bearing, &centred, 0.5, &out);
    check("no contact: penetration = -c and zero forces",
          fabs(out.penetration + C) < 1e-15 && out.normal_force == 0.0 && out.journal.fx == 0.0 &&
              out.bearing.moment == 0.0);

    /* Bad input never crashes. */
    ClrBodyState nan_state = journal;
    nan_state.vx = NAN;
    status_is("NaN body state -> NON_FINITE",
              clr_revolute_joint_forces(joint, ln, fr, &bearing, &nan_state, 0.5, &out),
              CLR_STATUS_NON_FINITE);
    status_is("NULL bearing state -> NULL_POINTER",
              clr_revolute_joint_forces(joint, ln, fr, NULL, &journal, 0.5, &out),
              CLR_STATUS_NULL_POINTER);
    status_is("NULL joint -> NULL_POINTER",
              clr_revolute_joint_forces(NULL, ln, fr, &bearing, &journal, 0.5, &out),
              CLR_STATUS_NULL_POINTER);
    ClrRevoluteJoint *bad = NULL;
    status_is("R_j >= R_i -> INVALID_PARAMETER",
              clr_revolute_joint_new(RJ, RI, 0.0, 0.0, 0.0, 0.0, &bad), CLR_STATUS_INVALID_PARAMETER);
    check("no handle on failure", bad == NULL);

    clr_revolute_joint_free(joint);
    clr_normal_law_free(ln);
    clr_friction_law_free(fr);
}

/* LuGre (Canudas de Wit et al. 1995): at the steady state of a constant slip v, z_ss =
 * sgn(v) g(v)/sigma0 with g(v) = mu_c + (mu_s - mu_c) exp(-(v/v_s)^2), so z_dot = 0 and the
 * coefficient is mu = sgn(v) g(v) + sigma2 v, F_T = -mu F_N. Rel tol 1e-12: only rounding of
 * sigma0 z_ss/g separates the library from this closed form. */
static void lugre(void) {
    const double s0 = 1e5, s1 = 316.0, s2 = 0.4, mu_s = 0.3, mu_c = 0.2, v_s = 0.01, fn = 1000.0;
    ClrLuGre *law = NULL;
    status_is("create LuGre", clr_lugre_new(s0, s1, s2, mu_s, mu_c, v_s, &law), CLR_STATUS_OK);
    const double v[3] = {0.005, -0.02, 0.1};
    for (int i = 0; i < 3; i++) {
        double r = v[i] / v_s;
        double g = mu_c + (mu_s - mu_c) * exp(-r * r);
        double sgn = v[i] > 0.0 ? 1.0 : -1.0;
        double mu = sgn * g + s2 * v[i];
        ClrLuGreOutput out;
        memset(&out, 0, sizeof out);
        char what[96];
        snprintf(what, sizeof what, "LuGre evaluate status (v = %g)", v[i]);
        status_is(what, clr_lugre_evaluate(law, sgn * g / s0, v[i], fn, &out), CLR_STATUS_OK);
        snprintf(what, sizeof what, "LuGre steady state z_dot = 0 (v = %g)", v[i]);
        close_abs(what, out.z_dot, 0.0, 1e-15);
        snprintf(what, sizeof what, "LuGre steady mu = sgn(v) g(v) + sigma2 v (v = %g)", v[i]);
        close_rel(what, out.coefficient, mu, 1e-12);
        snprintf(what, sizeof what, "LuGre steady F_T = -mu F_N (v = %g)", v[i]);
        close_rel(what, out.friction_force, -mu * fn, 1e-12);
    }
    /* At rest with no deflection: no rate, no force. */
    ClrLuGreOutput rest;
    clr_lugre_evaluate(law, 0.0, 0.0, fn, &rest);
    check("LuGre at rest: z_dot = 0, F_T = 0", rest.z_dot == 0.0 && rest.friction_force == 0.0);
    status_is("LuGre NaN z -> NON_FINITE", clr_lugre_evaluate(law, NAN, 0.1, fn, &rest),
              CLR_STATUS_NON_FINITE);
    status_is("LuGre NULL out -> NULL_POINTER", clr_lugre_evaluate(law, 0.0, 0.1, fn, NULL),
              CLR_STATUS_NULL_POINTER);
    clr_lugre_free(law);
    ClrLuGre *bad = NULL;
    status_is("LuGre sigma0 = 0 -> INVALID_PARAMETER",
              clr_lugre_new(0.0, s1, s2, mu_s, mu_c, v_s, &bad), CLR_STATUS_INVALID_PARAMETER);
    check("LuGre: no handle on failure", bad == NULL);
    clr_lugre_free(NULL);
}

/* Translational clearance joint (Flores et al. 2008): a 40 mm x 20 mm slider in a 20.2 mm
 * guide fixed at the origin, at rest and pressed 10 um into the lower face. Linear normal law
 * k = 1e8 N/m, no damping: both lower corners carry F_N = k delta = 1000 N and the slider is
 * pushed up by 2000 N. */
static void translational(void) {
    const double w = 0.0202, l = 0.04, h = 0.02, delta = 10e-6, k = 1e8;
    ClrTranslationalJoint *joint = NULL;
    status_is("create translational joint",
              clr_translational_joint_new(w, l, h, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, &joint),
              CLR_STATUS_OK);
    ClrNormalLaw *lin =
        one_parameter_law("create linear law", CLR_ELASTIC_LINEAR, k, CLR_DAMPING_NONE, 1.0);
    ClrBodyState guide = {0};
    ClrBodyState slider = {0.0, -0.5 * (w - h) - delta, 0.0, 0.0, 0.0, 0.0};
    const double v0[4] = {0.1, 0.1, 0.1, 0.1};
    ClrTranslationalForces out;
    memset(&out, 0, sizeof out);
    status_is("translational forces status",
              clr_translational_joint_forces(joint, lin, NULL, &guide, &slider, v0, &out),
              CLR_STATUS_OK);
    check("slider on the lower face: two corners, one surface",
          out.configuration == CLR_CONFIGURATION_TWO_CORNERS_ONE_SURFACE);
    check("corners 0 and 1 on the lower face, 2 and 3 free",
          out.corners[0].active == 1 && out.corners[0].side == -1 && out.corners[1].active == 1 &&
              out.corners[1].side == -1 && out.corners[2].active == 0 && out.corners[3].active == 0);
    check("positive normal force at corner 0", out.corners[0].normal_force > 0.0);
    close_rel("corner 0 penetration = 10 um", out.corners[0].penetration, delta, 1e-6);
    close_rel("corner 0 F_N = k delta = 1000 N", out.corners[0].normal_force, k * delta, 1e-6);
    close_rel("slider pushed up by 2000 N", out.slider.fy, 2.0 * k * delta, 1e-6);
    close_rel("guide pushed down by 2000 N", out.guide.fy, -2.0 * k * delta, 1e-6);
    close_abs("no net moment on the slider", out.slider.moment, 0.0, 1e-9);

    /* Centred slider: free flight, zero forces. */
    ClrBodyState centred = {0};
    clr_translational_joint_forces(joint, lin, NULL, &guide, &centred, v0, &out);
    check("centred slider: free flight, zero forces",
          out.configuration == CLR_CONFIGURATION_FREE_FLIGHT && out.slider.fy == 0.0 &&
              out.corners[0].active == 0);
    status_is("NULL impact velocities -> NULL_POINTER",
              clr_translational_joint_forces(joint, lin, NULL, &guide, &slider, NULL, &out),
              CLR_STATUS_NULL_POINTER);
    ClrTranslationalJoint *bad = NULL;
    status_is("W <= h -> INVALID_PARAMETER",
              clr_translational_joint_new(h, l, h, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, &bad),
              CLR_STATUS_INVALID_PARAMETER);
    check("translational: no handle on failure", bad == NULL);
    clr_translational_joint_free(joint);
    clr_translational_joint_free(NULL);
    clr_normal_law_free(lin);
}

/* Evaluate a multipoint joint with N = 3, M = 0 (16 point ids, delta_dot_minus = 0.1 m/s each)
 * without friction, the guide body at rest at the origin; `what` names the status check. */
static ClrMultipointForces multipoint_on_fixed_guide(const char *what, ClrMultipointJoint *joint,
                                                     const ClrNormalLaw *law, ClrBodyState slider) {
    const ClrBodyState guide = {0};
    double v0[16];
    for (int i = 0; i < 16; i++) v0[i] = 0.1;
    ClrMultipointForces out;
    memset(&out, 0, sizeof out);
    status_is(what, clr_multipoint_joint_forces(joint, law, NULL, &guide, &slider, v0, 16, &out),
              CLR_STATUS_OK);
    return out;
}

/* Multipoint contact, closed form (contact-laws.md §3.2): a 40 mm x 20 mm slider lying flat on a
 * straight guide fixed at the origin (surface y = 0, slider above it), at rest and pressed
 * delta = 10 um into it; N = 3 points per face, no reverse check. Linear law k = 1e8 N/m, no
 * damping: the 5 candidates of the bottom face (2 corners, 3 face points, spacing L/4 = 10 mm)
 * each carry F_N = k delta = 1000 N (area contact of face 0), the slider is pushed up by
 * 5000 N with no moment, the guide pushed down by 5000 N whose moment about the origin is
 * -sum(x_i) 1000 N = -500 N m. Tributary lengths: 5 mm at the corners, 10 mm inside (sum L).
 * Rel 1e-6 as for the translational joint (delta is the difference of coordinates ~1e-2 m). */
static void multipoint(void) {
    const double l = 0.04, h = 0.02, delta = 10e-6, k = 1e8, x0 = 0.1;
    ClrMultipointJoint *joint = NULL;
    status_is("create multipoint joint (straight guide)",
              clr_multipoint_joint_new_straight(1.0, 1, l, h, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 3, 0,
                                                &joint),
              CLR_STATUS_OK);
    size_t n_ids = 0;
    status_is("point count status", clr_multipoint_joint_point_count(joint, &n_ids), CLR_STATUS_OK);
    check("point count = 4 + 4N + M = 16", n_ids == 16);
    ClrNormalLaw *lin = one_parameter_law("create linear law (multipoint)", CLR_ELASTIC_LINEAR, k,
                                          CLR_DAMPING_NONE, 1.0);
    ClrBodyState slider = {x0, 0.5 * h - delta, 0.0, 0.0, 0.0, 0.0};
    ClrMultipointForces out =
        multipoint_on_fixed_guide("multipoint forces status", joint, lin, slider);
    check("flat face on the guide: area contact of face 0",
          out.contact_class == CLR_CONTACT_CLASS_AREA && out.area_face == 0);
    check("5 active points", out.active_points == 5);
    close_rel("contact length = L = 40 mm", out.contact_length, l, 1e-9);
    close_rel("slider pushed up by 5 k delta = 5000 N", out.slider.fy, 5.0 * k * delta, 1e-6);
    close_rel("guide pushed down by 5000 N", out.guide.fy, -5.0 * k * delta, 1e-6);
    close_abs("no tangential force without friction", out.slider.fx, 0.0, 0.0);
    close_abs("no net moment on the slider", out.slider.moment, 0.0, 1e-9);
    close_rel("guide moment about its origin = -500 N m", out.guide.moment, -5.0 * x0 * k * delta,
              1e-6);

    ClrMultipointContact pts[16];
    size_t count = 0;
    status_is("read points", clr_multipoint_joint_points(joint, pts, 16, &count), CLR_STATUS_OK);
    check("5 points read", count == 5);
    const size_t ids[5] = {0, 4, 5, 6, 1}; /* corner 0, face 0 points 0..2, corner 1, by arc */
    for (size_t i = 0; i < count && i < 5; i++) {
        char what[96];
        double x = x0 - 0.5 * l + 0.25 * l * (double)i;
        snprintf(what, sizeof what, "point %zu: id %zu, normal (0, -1)", i, ids[i]);
        check(what, pts[i].id == ids[i] && pts[i].normal_x == 0.0 && pts[i].normal_y == -1.0 &&
                        pts[i].source == (i == 0 || i == 4 ? CLR_POINT_SOURCE_CORNER
                                                           : CLR_POINT_SOURCE_FACE));
        snprintf(what, sizeof what, "point %zu: arc = x = %g m", i, x);
        close_rel(what, pts[i].arc, x, 1e-12);
        snprintf(what, sizeof what, "point %zu: penetration = 10 um", i);
        close_rel(what, pts[i].penetration, delta, 1e-6);
        snprintf(what, sizeof what, "point %zu: F_N = k delta = 1000 N", i);
        close_rel(what, pts[i].normal_force, k * delta, 1e-6);
        snprintf(what, sizeof what, "point %zu: tributary length", i);
        close_rel(what, pts[i].tributary_length, (i == 0 || i == 4 ? 0.125 : 0.25) * l, 1e-9);
    }

    /* Buffers, counts and bad input. */
    ClrBodyState guide = {0};
    double v0[16];
    for (int i = 0; i < 16; i++) v0[i] = 0.1;
    ClrMultipointContact two[2];
    two[0].id = 999;
    count = 0;
    status_is("2-entry buffer -> BUFFER_TOO_SMALL",
              clr_multipoint_joint_points(joint, two, 2, &count), CLR_STATUS_BUFFER_TOO_SMALL);
    check("count needed = 5, nothing copied", count == 5 && two[0].id == 999);
    check("message gives the count", strstr(clr_last_error_message(), "5 are needed") != NULL);
    count = 0;
    status_is("count query (NULL, 0)", clr_multipoint_joint_points(joint, NULL, 0, &count),
              CLR_STATUS_BUFFER_TOO_SMALL);
    check("count query gives 5", count == 5);
    out.active_points = 12345;
    status_is("15 impact velocities for 16 -> INVALID_ARGUMENT",
              clr_multipoint_joint_forces(joint, lin, NULL, &guide, &slider, v0, 15, &out),
              CLR_STATUS_INVALID_ARGUMENT);
    status_is("NULL impact velocities -> NULL_POINTER",
              clr_multipoint_joint_forces(joint, lin, NULL, &guide, &slider, NULL, 16, &out),
              CLR_STATUS_NULL_POINTER);
    ClrBodyState nan_state = slider;
    nan_state.omega = NAN;
    status_is("NaN slider state -> NON_FINITE",
              clr_multipoint_joint_forces(joint, lin, NULL, &guide, &nan_state, v0, 16, &out),
              CLR_STATUS_NON_FINITE);
    v0[15] = INFINITY;
    status_is("infinite impact velocity -> NON_FINITE",
              clr_multipoint_joint_forces(joint, lin, NULL, &guide, &slider, v0, 16, &out),
              CLR_STATUS_NON_FINITE);
    check("output untouched on failure", out.active_points == 12345);
    status_is("points still those of the last good evaluation",
              clr_multipoint_joint_points(joint, pts, 16, &count), CLR_STATUS_OK);
    check("still 5 points", count == 5);
    status_is("reset", clr_multipoint_joint_reset(joint), CLR_STATUS_OK);
    clr_multipoint_joint_points(joint, NULL, 0, &count);
    check("no points after reset", count == 0);
    ClrMultipointJoint *bad = NULL;
    status_is("gap_on_left = 2 -> INVALID_ARGUMENT",
              clr_multipoint_joint_new_straight(1.0, 2, l, h, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 3, 0,
                                                &bad),
              CLR_STATUS_INVALID_ARGUMENT);
    status_is("slider length 0 -> INVALID_PARAMETER",
              clr_multipoint_joint_new_straight(1.0, 1, 0.0, h, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 3, 0,
                                                &bad),
              CLR_STATUS_INVALID_PARAMETER);
    status_is("sine span 0 -> INVALID_PARAMETER",
              clr_multipoint_joint_new_sine(40e-6, 0.0, l, h, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 3, 0,
                                            &bad),
              CLR_STATUS_INVALID_PARAMETER);
    check("multipoint: no handle on failure", bad == NULL);
    clr_multipoint_joint_free(joint);
    clr_multipoint_joint_free(NULL);
    clr_normal_law_free(lin);
}

/* Multipoint contact on the hogging guide of contact-laws.md §7.8: y = A sin(pi x), A = 40 um,
 * span 1 m, fixed (guide state at the origin, at rest); slider 0.1 m x 0.02 m with its bottom
 * face at 39.5 um over x = 0.45 .. 0.55, N = 3: penetrations 7.534e-9, 3.767e-7, 5.000e-7,
 * 3.767e-7, 7.534e-9 m (4 digits -> rel 1e-3), and the closed form A sin(pi x) - 39.5 um to
 * rel 1e-6 (the normal-direction correction is O(slope^2) ~ 1e-9). */
static void multipoint_sine(void) {
    const double amp = 40e-6, bottom = 39.5e-6;
    ClrMultipointJoint *joint = NULL;
    status_is("create multipoint joint (sine guide)",
              clr_multipoint_joint_new_sine(amp, 1.0, 0.1, 0.02, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 3, 0,
                                            &joint),
              CLR_STATUS_OK);
    ClrNormalLaw *hz = one_parameter_law("create Hertz law (sine)", CLR_ELASTIC_HERTZ, 1e10,
                                         CLR_DAMPING_NONE, 1.0);
    ClrBodyState slider = {0.5, bottom + 0.01, 0.0, 0.0, 0.0, 0.0};
    ClrMultipointForces out = multipoint_on_fixed_guide("sine forces status", joint, hz, slider);
    check("7.8 area contact of face 0, 5 points",
          out.contact_class == CLR_CONTACT_CLASS_AREA && out.area_face == 0 &&
              out.active_points == 5);
    ClrMultipointContact pts[16];
    size_t count = 0;
    clr_multipoint_joint_points(joint, pts, 16, &count);
    const double expected[5] = {7.534e-9, 3.767e-7, 5.000e-7, 3.767e-7, 7.534e-9};
    const double pi = 3.14159265358979323846;
    for (size_t i = 0; i < count && i < 5; i++) {
        char what[96];
        double x = 0.45 + 0.025 * (double)i;
        snprintf(what, sizeof what, "7.8 penetration at x = %g = %.4g m", x, expected[i]);
        close_rel(what, pts[i].penetration, expected[i], 1e-3);
        snprintf(what, sizeof what, "7.8 penetration at x = %g = A sin(pi x) - 39.5 um", x);
        close_rel(what, pts[i].penetration, amp * sin(pi * x) - bottom, 1e-6);
    }
    close_abs("7.8 symmetric: no tangential force", out.slider.fx, 0.0, 1e-9 * out.slider.fy);
    clr_multipoint_joint_free(joint);
    clr_normal_law_free(hz);
}

/* Multipoint contact against clr-contact itself: tests/c_program.rs computes the case
 * CLR_MP_* (a tilted slider sliding and spinning on a straight guide on a moving, rotated body;
 * line contact of 4 points, Hertz + Lankarani-Nikravesh, Coulomb friction) with clr-contact's
 * detector directly and passes the results here, printed to round trip. The C API runs the same
 * code, so the values agree to rounding: rel 1e-12 (abs 1e-18 m for values near zero). The
 * second evaluation (warm started from the first) must give the same values. */
#ifndef CLR_MP_EXPECTED
#error "tests/c_program.rs passes the multipoint case CLR_MP_* with -D"
#endif
static int rust_values = 0, rust_identical = 0;

static void close_rust(const char *what, double got, double expected) {
    int ok = fabs(got - expected) <= 1e-12 * fabs(expected) + 1e-18;
    rust_values++;
    rust_identical += got == expected;
    if (!ok) printf("     %s: got %.17g, clr-contact %.17g\n", what, got, expected);
    check(what, ok);
}

static void multipoint_rust(void) {
    static const double jp[] = CLR_MP_JOINT;
    static const double laws[] = CLR_MP_LAWS;
    static const double g[] = CLR_MP_GUIDE;
    static const double sl[] = CLR_MP_SLIDER;
    static const double v0[] = CLR_MP_IMPACT;
    static const double ex[] = CLR_MP_EXPECTED;
    static const double ep[] = CLR_MP_POINTS;
    const size_t n_v0 = sizeof v0 / sizeof v0[0], n_pts = sizeof ep / sizeof ep[0] / 17;
    ClrMultipointJoint *joint = NULL;
    status_is("create the clr-contact case",
              clr_multipoint_joint_new_straight(jp[0], (int32_t)jp[1], jp[2], jp[3], jp[4], jp[5],
                                                jp[6], jp[7], jp[8], jp[9], (size_t)jp[10],
                                                (size_t)jp[11], &joint),
              CLR_STATUS_OK);
    size_t n_ids = 0;
    clr_multipoint_joint_point_count(joint, &n_ids);
    check("point count = number of impact velocities", n_ids == n_v0);
    double fp[2] = {laws[2], laws[3]};
    ClrNormalLaw *law = one_parameter_law("create the Hertz law of the clr-contact case",
                                          CLR_ELASTIC_HERTZ, laws[0],
                                          CLR_DAMPING_LANKARANI_NIKRAVESH, laws[1]);
    ClrFrictionLaw *fr = NULL;
    clr_friction_law_new(CLR_FRICTION_COULOMB, fp, 2, &fr);
    ClrBodyState guide = {g[0], g[1], g[2], g[3], g[4], g[5]};
    ClrBodyState slider = {sl[0], sl[1], sl[2], sl[3], sl[4], sl[5]};
    for (int pass = 0; pass < 2; pass++) {
        char what[128];
        ClrMultipointForces out;
        memset(&out, 0, sizeof out);
        snprintf(what, sizeof what, "clr-contact case, evaluation %d: status", pass + 1);
        status_is(what, clr_multipoint_joint_forces(joint, law, fr, &guide, &slider, v0, n_v0, &out),
                  CLR_STATUS_OK);
        snprintf(what, sizeof what, "evaluation %d: class, face, %zu points", pass + 1, n_pts);
        check(what, out.contact_class == (ClrContactClass)ex[0] && out.area_face == (int32_t)ex[1] &&
                        out.active_points == (size_t)ex[2] && out.active_points == n_pts);
        const double got[7] = {out.contact_length, out.guide.fx,  out.guide.fy, out.guide.moment,
                               out.slider.fx,      out.slider.fy, out.slider.moment};
        const char *names[7] = {"contact length", "guide f_x", "guide f_y", "guide moment",
                                "slider f_x",     "slider f_y", "slider moment"};
        for (int i = 0; i < 7; i++) {
            snprintf(what, sizeof what, "evaluation %d: %s = clr-contact", pass + 1, names[i]);
            close_rust(what, got[i], ex[3 + i]);
        }
        ClrMultipointContact pts[64];
        size_t count = 0;
        clr_multipoint_joint_points(joint, pts, 64, &count);
        for (size_t i = 0; i < count && i < n_pts; i++) {
            const double *e = ep + 17 * i;
            const ClrMultipointContact *p = &pts[i];
            snprintf(what, sizeof what, "evaluation %d, point %zu: id, source, face, index",
                     pass + 1, i);
            check(what, p->id == (size_t)e[0] && p->source == (ClrPointSource)e[1] &&
                            p->face == (int32_t)e[2] && p->index == (size_t)e[3]);
            const double vals[13] = {p->arc,      p->penetration,     p->normal_x,
                                     p->normal_y, p->slider_x,        p->slider_y,
                                     p->guide_x,  p->guide_y,         p->normal_velocity,
                                     p->tangential_velocity,          p->tributary_length,
                                     p->normal_force,                 p->tangential_force};
            const char *fields[13] = {"arc", "penetration", "normal_x", "normal_y", "slider_x",
                                      "slider_y", "guide_x", "guide_y", "v_N", "v_T",
                                      "tributary length", "F_N", "F_T"};
            for (int f = 0; f < 13; f++) {
                snprintf(what, sizeof what, "evaluation %d, point %zu: %s = clr-contact", pass + 1,
                         i, fields[f]);
                close_rust(what, vals[f], e[4 + f]);
            }
        }
    }
    printf("     clr-contact case: %d of %d values identical to clr-contact's\n", rust_identical,
           rust_values);
    clr_multipoint_joint_free(joint);
    clr_normal_law_free(law);
    clr_friction_law_free(fr);
}

/* Whole model from a model file's text: a driven crank whose pin sits with 0.1 mm radial
 * clearance in a spring-held link (tests/data/journal_bearing.toml without [output] t_end, which
 * clr_model_run gives). Checks the run reaches t_end, columns have one value per row, the
 * contact force is never negative and the metric and impact count are readable. */
static const char *JOURNAL_MODEL =
    "[model]\n"
    "name = \"journal_bearing\"\n"
    "gravity = [0.0, -9.81]\n"
    "[[body]]\n"
    "name = \"crank\"\n"
    "mass = 0.5\n"
    "inertia = 1.7e-3\n"
    "position = [0.05, 0.0]\n"
    "[[body]]\n"
    "name = \"link\"\n"
    "mass = 1.0\n"
    "inertia = 1.0e-2\n"
    "position = [0.25, 0.0]\n"
    "velocity = [0.0, 0.0]\n"
    "angular_velocity = 0.0\n"
    "[[joint]]\n"
    "name = \"shaft\"\n"
    "type = \"revolute\"\n"
    "a = { body = \"ground\", at = [0.0, 0.0] }\n"
    "b = { body = \"crank\", at = [-0.05, 0.0] }\n"
    "[[driver]]\n"
    "name = \"motor\"\n"
    "type = \"angle\"\n"
    "body = \"crank\"\n"
    "motion = { type = \"ramp\", initial = 0.0, rate = 20.0, duration = 0.05 }\n"
    "[[force]]\n"
    "name = \"holder\"\n"
    "type = \"spring_damper\"\n"
    "a = { body = \"ground\", at = [0.5, 0.0] }\n"
    "b = { body = \"link\", at = [0.15, 0.0] }\n"
    "stiffness = 2000.0\n"
    "damping = 5.0\n"
    "free_length = 0.1\n"
    "[[clearance]]\n"
    "name = \"pin\"\n"
    "type = \"revolute\"\n"
    "bearing = { body = \"link\", at = [-0.15, 0.0] }\n"
    "journal = { body = \"crank\", at = [0.05, 0.0] }\n"
    "bearing_radius = 0.0100\n"
    "journal_radius = 0.0099\n"
    "normal = { law = \"hertz-internal-cylinder\", damping = \"lankarani-nikravesh\", "
    "restitution = 0.9, bearing_material = { youngs_modulus = 2.07e11, poisson_ratio = 0.3 }, "
    "journal_material = { youngs_modulus = 2.07e11, poisson_ratio = 0.3 } }\n"
    "friction = { law = \"coulomb\", mu = 0.05, v_reg = 1e-3 }\n"
    "[solver]\n"
    "rtol = 1e-6\n"
    "atol = 1e-9\n";

static void model(void) {
    ClrModel *m = NULL;
    status_is("model from TOML text", clr_model_from_toml(JOURNAL_MODEL, &m), CLR_STATUS_OK);
    const double *t = NULL;
    size_t n = 0;
    status_is("column before the first run -> MODEL_ERROR", clr_model_column(m, "t", &t, &n),
              CLR_STATUS_MODEL_ERROR);
    status_is("run to 0.1 s", clr_model_run(m, 0.1), CLR_STATUS_OK);
    status_is("column t", clr_model_column(m, "t", &t, &n), CLR_STATUS_OK);
    check("several output rows", n > 10);
    close_abs("first row at t = 0 s", t[0], 0.0, 0.0);
    close_rel("last row at t_end = 0.1 s", t[n - 1], 0.1, 1e-12);
    const double *fn = NULL;
    size_t n_fn = 0;
    status_is("column pin.normal_force", clr_model_column(m, "pin.normal_force", &fn, &n_fn),
              CLR_STATUS_OK);
    int nonneg = n_fn == n;
    double peak_rows = 0.0;
    for (size_t i = 0; i < n_fn; i++) {
        nonneg = nonneg && fn[i] >= 0.0;
        if (fn[i] > peak_rows) peak_rows = fn[i];
    }
    check("pin.normal_force: one value per row, all >= 0 N", nonneg);
    double peak = NAN;
    status_is("metric pin.peak_normal_force", clr_model_metric(m, "pin.peak_normal_force", &peak),
              CLR_STATUS_OK);
    check("peak metric >= largest recorded row", peak >= peak_rows);
    size_t impacts = 12345;
    status_is("impact count", clr_model_impact_count(m, &impacts), CLR_STATUS_OK);
    check("impact count written", impacts != 12345);
    printf("     model: %zu rows, %zu impacts, peak F_N = %.6g N\n", n, impacts, peak);
    status_is("unknown column -> UNKNOWN_NAME", clr_model_column(m, "pin.nope", &t, &n),
              CLR_STATUS_UNKNOWN_NAME);
    check("message lists the columns", strstr(clr_last_error_message(), "pin.normal_force") != NULL);
    status_is("t_end <= 0 -> MODEL_ERROR", clr_model_run(m, 0.0), CLR_STATUS_MODEL_ERROR);
    clr_model_free(m);

    ClrModel *bad = NULL;
    status_is("malformed model -> MODEL_ERROR", clr_model_from_toml("[model]\nname = 3\n", &bad),
              CLR_STATUS_MODEL_ERROR);
    check("model: no handle on failure", bad == NULL);
    clr_model_free(NULL);
}

/* Error handling: status codes, messages, outputs untouched on failure. */
static void errors(void) {
    ClrNormalLaw *law = NULL;
    double p[6] = {E, NU, RI, E, NU, RJ};
    status_is("c_e = 1.5 -> INVALID_PARAMETER",
              clr_normal_law_new(CLR_ELASTIC_HERTZ_INTERNAL_CYLINDER, p, 6,
                                 CLR_DAMPING_LANKARANI_NIKRAVESH, 1.5, &law),
              CLR_STATUS_INVALID_PARAMETER);
    check("message names c_e", strstr(clr_last_error_message(), "c_e") != NULL);
    check("no handle on failure", law == NULL);
    status_is("5 parameters for 6 -> INVALID_ARGUMENT",
              clr_normal_law_new(CLR_ELASTIC_HERTZ_INTERNAL_CYLINDER, p, 5, CLR_DAMPING_NONE, 0.5, &law),
              CLR_STATUS_INVALID_ARGUMENT);
    check("message lists the parameters", strstr(clr_last_error_message(), "R_journal") != NULL);
    status_is("unknown elastic code -> INVALID_ARGUMENT",
              clr_normal_law_new(99, p, 6, CLR_DAMPING_NONE, 0.5, &law), CLR_STATUS_INVALID_ARGUMENT);
    status_is("unknown damping code -> INVALID_ARGUMENT",
              clr_normal_law_new(CLR_ELASTIC_HERTZ, p, 1, 1234, 0.5, &law), CLR_STATUS_INVALID_ARGUMENT);
    status_is("NULL params -> NULL_POINTER",
              clr_normal_law_new(CLR_ELASTIC_HERTZ, NULL, 1, CLR_DAMPING_NONE, 0.5, &law),
              CLR_STATUS_NULL_POINTER);
    status_is("NULL out -> NULL_POINTER",
              clr_normal_law_new(CLR_ELASTIC_HERTZ, p, 1, CLR_DAMPING_NONE, 0.5, NULL),
              CLR_STATUS_NULL_POINTER);
    double pereira[3] = {e_star(), 11e-3, L};
    status_is("Pereira with Delta R = 11 mm -> OUT_OF_VALIDITY",
              clr_normal_law_new(CLR_ELASTIC_PEREIRA_INTERNAL, pereira, 3, CLR_DAMPING_NONE, 1.0, &law),
              CLR_STATUS_OUT_OF_VALIDITY);
    ClrJournalBearing jb = clr_journal_bearing_flap_paper_test();
    status_is("unknown preset -> UNKNOWN_NAME", clr_normal_law_preset("Foo", &jb, 0.5, &law),
              CLR_STATUS_UNKNOWN_NAME);
    check("message lists the presets", strstr(clr_last_error_message(), "Gonthier") != NULL);
    status_is("NULL preset name -> NULL_POINTER", clr_normal_law_preset(NULL, &jb, 0.5, &law),
              CLR_STATUS_NULL_POINTER);
    status_is("NULL geometry -> NULL_POINTER", clr_normal_law_preset("LN", NULL, 0.5, &law),
              CLR_STATUS_NULL_POINTER);
    status_is("invalid UTF-8 name -> INVALID_ARGUMENT",
              clr_normal_law_preset("\xff\xfe", &jb, 0.5, &law), CLR_STATUS_INVALID_ARGUMENT);
    check("still no handle", law == NULL);

    double f = 123.0;
    status_is("NULL law -> NULL_POINTER", clr_normal_law_force(NULL, 1e-5, 0.0, 0.5, &f),
              CLR_STATUS_NULL_POINTER);
    law = internal_law(CLR_DAMPING_LANKARANI_NIKRAVESH);
    status_is("NaN delta -> NON_FINITE", clr_normal_law_force(law, NAN, 0.0, 0.5, &f),
              CLR_STATUS_NON_FINITE);
    status_is("inf delta_dot -> NON_FINITE", clr_normal_law_force(law, 1e-5, INFINITY, 0.5, &f),
              CLR_STATUS_NON_FINITE);
    check("output untouched on failure", f == 123.0);
    check("message names delta", strstr(clr_last_error_message(), "delta_dot") != NULL);
    clr_normal_law_free(law);

    ClrFrictionLaw *fr = NULL;
    double bad[3] = {0.1, 1e-3, 1e-4};
    status_is("Ambrosio v1 < v0 -> INVALID_PARAMETER",
              clr_friction_law_new(CLR_FRICTION_AMBROSIO, bad, 3, &fr), CLR_STATUS_INVALID_PARAMETER);
    status_is("NULL friction law -> NULL_POINTER", clr_friction_law_force(fr, 0.1, 1.0, &f),
              CLR_STATUS_NULL_POINTER);
    double thr[2] = {0.1, 0.01};
    clr_friction_law_new(CLR_FRICTION_THRELFALL, thr, 2, &fr);
    status_is("NaN F_N -> NON_FINITE", clr_friction_law_force(fr, 0.1, NAN, &f), CLR_STATUS_NON_FINITE);
    clr_friction_law_free(fr);
    status_is("negative chi -> INVALID_PARAMETER", clr_effective_restitution(-1.0, &f),
              CLR_STATUS_INVALID_PARAMETER);

    clr_normal_law_free(NULL);
    clr_friction_law_free(NULL);
    clr_revolute_joint_free(NULL);
    check("free(NULL) is a no-op", 1);
    check("version string = " CLR_EXPECTED_VERSION, strcmp(clr_version(), CLR_EXPECTED_VERSION) == 0);
}

int main(void) {
    normal_laws();
    restitution();
    friction();
    revolute();
    lugre();
    translational();
    multipoint();
    multipoint_sine();
    multipoint_rust();
    model();
    errors();
    printf("%d passed, %d failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}
