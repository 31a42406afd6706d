/*
 * Plans every planner-A, planner-B (mean elements, and the other input forms through
 * reconfig_impulsive_solve_form), GEO-tour, LEO-arc and hybrid-transfer fixture through the C
 * interface and prints,
 * per fixture, the status, the cost (planner A: J) or total delta-v (planner B), their raw bits,
 * and a checksum over the bits of the whole returned trajectory or plan.
 *
 * The fixtures reach C as `fixture_data.h`, generated from the fixture files by the test
 * tests/tests/c_api.rs (hex-float literals, so every number is exact). Build, as that test does:
 *
 *   cargo build --release -p reconfig-capi
 *   cc -std=c99 -O2 -I capi/include -I <dir of fixture_data.h> examples/c/plan_fixtures.c \
 *      target/release/libreconfig_capi.a -lpthread -ldl -lm -o plan_fixtures
 *
 * The workspaces are caller memory: here static arrays (one per planner, this program is one
 * task), sized at run time against reconfig_*_workspace_size().
 *
 * A request outside the built-in limits (the flight service's) is refused, not solved: the
 * `+fixed-point` runs ask for nonlinear_correction = 0, and print the refusal with the name
 * reconfig_setting_name gives its error.index. The first LEO arc is also asked with
 * min_gap_s = -1 (outside its range [0, duration / 8]): refused, named the same way. The first
 * hybrid transfer is also asked with its arrival velocity moved off the halo orbit (1e-3 LU/TU
 * on its y component): refused RECONFIG_HYBRID_ERR_NOT_ON_PERIODIC_ORBIT, the miss and the
 * tolerance. The hybrid solve is stack-only (about 74 KB on the Cortex-M7): main's thread has
 * plenty.
 */
#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#include "reconfig.h"
#include "cases.h"
#include "checksum.h"
#include "fixture_data.h"

/* Caller-owned workspaces. 8-byte alignment is checked against reconfig_*_workspace_align(). */
#define A_WORKSPACE_BYTES (300u * 1024u)
#define B_WORKSPACE_BYTES (64u * 1024u)
static uint64_t a_workspace[A_WORKSPACE_BYTES / 8];
static uint64_t b_workspace[B_WORKSPACE_BYTES / 8];
static ReconfigASolution a_solution;
static ReconfigBSolution b_solution;
static ReconfigBFormSolution f_solution;
#define GEO_WORKSPACE_BYTES (64u * 1024u)
static uint64_t geo_workspace[GEO_WORKSPACE_BYTES / 8];
static ReconfigGeoSolution g_solution;
#define LEO_WORKSPACE_BYTES (32u * 1024u)
static uint64_t leo_workspace[LEO_WORKSPACE_BYTES / 8];
static ReconfigLeoArcSolution l_solution;
#define HYBRID_WORKSPACE_BYTES (8u * 1024u)
static uint64_t hybrid_workspace[HYBRID_WORKSPACE_BYTES / 8];
static ReconfigHybridSolution h_solution;

/* A refusal: its code, field and index, the setting's name when the refusal names a setting
 * (reconfig_setting_name), and the bits of the value and the limit. */
static void print_refusal(char kind, const char *name, int32_t planner, int32_t status,
                          const ReconfigError *e) {
    const char *setting = 0;
    if (status == RECONFIG_ERR_SETTING_OUT_OF_RANGE || status == RECONFIG_ERR_LIMIT_EXCEEDED)
        setting = reconfig_setting_name(planner, e->index);
    printf("%c %s status=%" PRId32 " field=%" PRId32 " index=%" PRId32 " setting=%s value_bits=%016"
           PRIx64 " limit_bits=%016" PRIx64 "\n",
           kind, name, status, e->field, e->index, setting ? setting : "-", bits(e->value),
           bits(e->limit));
}

static int plan_a(void) {
    ReconfigASettings settings;
    if (reconfig_pseudospectral_default_settings(&settings) != 0) return 1;
    for (size_t c = 0; c < sizeof A_CASES / sizeof A_CASES[0]; c++) {
        int32_t status = reconfig_pseudospectral_solve(a_workspace, &A_CASES[c].problem,
                                                       &settings, &a_solution);
        uint64_t h = UINT64_C(0xcbf29ce484222325);
        for (int s = 0; s < RECONFIG_A_MAX_SPACECRAFT; s++)
            for (int n = 0; n < RECONFIG_A_MAX_NODES; n++) {
                for (int k = 0; k < 6; k++) h = mix(h, a_solution.states_lu_lutu[s][n][k]);
                for (int k = 0; k < 3; k++) h = mix(h, a_solution.controls_fu[s][n][k]);
            }
        if (status < 0) {
            print_refusal('A', A_CASES[c].name, RECONFIG_PLANNER_PSEUDOSPECTRAL, status,
                          &a_solution.error);
            continue;
        }
        printf("A %s status=%" PRId32 " usable=%u J=%.9f J_bits=%016" PRIx64
               " min_sep_bits=%016" PRIx64 " work_units=%" PRIu64 " checksum=%016" PRIx64 "\n",
               A_CASES[c].name, status, (unsigned)a_solution.usable, a_solution.cost_fu2_tu,
               bits(a_solution.cost_fu2_tu), bits(a_solution.min_separation_lu),
               a_solution.work_units, h);
    }
    return 0;
}

static int plan_b(void) {
    ReconfigBSettings defaults;
    if (reconfig_impulsive_default_settings(&defaults) != 0) return 1;
    for (size_t c = 0; c < sizeof B_CASES / sizeof B_CASES[0]; c++) {
        ReconfigBSettings settings = defaults;
        if (B_CASES[c].fixed_point_only) {
            settings.min_fuel = 0;
            settings.nonlinear_correction = 0;
        }
        int32_t status = reconfig_impulsive_solve(b_workspace, &B_CASES[c].problem, &settings,
                                                  &b_solution);
        if (status < 0) {
            print_refusal('B', B_CASES[c].name, RECONFIG_PLANNER_IMPULSIVE, status,
                          &b_solution.error);
            continue;
        }
        uint64_t h = UINT64_C(0xcbf29ce484222325);
        for (int i = 0; i < b_solution.impulse_count; i++) {
            h = mix(h, b_solution.impulses[i].time_s);
            for (int k = 0; k < 3; k++) h = mix(h, b_solution.impulses[i].dv_rtn_mps[k]);
        }
        h = mix(h, b_solution.terminal_position_error_m);
        printf("B %s status=%" PRId32 " usable=%u impulses=%u dv_mps=%.9f dv_bits=%016" PRIx64
               " work_units=%" PRIu64 " checksum=%016" PRIx64 "\n",
               B_CASES[c].name, status, (unsigned)b_solution.usable,
               (unsigned)b_solution.impulse_count, b_solution.total_dv_mps,
               bits(b_solution.total_dv_mps), b_solution.work_units, h);
    }
    return 0;
}

/* The same workspace as planner B's mean-element form: one planner-B workspace serves both. */
static int plan_f(void) {
    ReconfigBSettings defaults;
    if (reconfig_impulsive_default_settings(&defaults) != 0) return 1;
    for (size_t c = 0; c < sizeof F_CASES / sizeof F_CASES[0]; c++) {
        ReconfigBSettings settings = defaults;
        if (F_CASES[c].fixed_point_only) {
            settings.min_fuel = 0;
            settings.nonlinear_correction = 0;
        }
        int32_t status = reconfig_impulsive_solve_form(b_workspace, &F_CASES[c].problem,
                                                       &settings, &f_solution);
        const ReconfigBSolution *p = &f_solution.plan;
        if (status < 0) {
            print_refusal('F', F_CASES[c].name, RECONFIG_PLANNER_IMPULSIVE, status, &p->error);
            continue;
        }
        uint64_t h = UINT64_C(0xcbf29ce484222325);
        for (int i = 0; i < p->impulse_count; i++) {
            h = mix(h, p->impulses[i].time_s);
            for (int k = 0; k < 3; k++) h = mix(h, p->impulses[i].dv_rtn_mps[k]);
        }
        h = mix(h, p->terminal_position_error_m);
        printf("F %s status=%" PRId32 " usable=%u impulses=%u dv_mps=%.9f dv_bits=%016" PRIx64
               " work_units=%" PRIu64 " checksum=%016" PRIx64 " end_form=%u end_checksum=%016"
               PRIx64 "\n",
               F_CASES[c].name, status, (unsigned)p->usable, (unsigned)p->impulse_count,
               p->total_dv_mps, bits(p->total_dv_mps), p->work_units, h,
               (unsigned)f_solution.end.form,
               end_checksum(UINT64_C(0xcbf29ce484222325), &f_solution.end));
    }
    return 0;
}

static int plan_g(void) {
    for (size_t c = 0; c < sizeof G_CASES / sizeof G_CASES[0]; c++) {
        int32_t status = reconfig_geo_tour_solve(geo_workspace, &G_CASES[c].problem,
                                                 &G_CASES[c].settings, &g_solution);
        if (status < 0) {
            print_refusal('G', G_CASES[c].name, RECONFIG_PLANNER_GEO_TOUR, status,
                          &g_solution.error);
            continue;
        }
        /* The fastest tour is printed only when the solution has one (has_fastest_tour_s). */
        printf("G %s status=%" PRId32 " usable=%u legs=%u dv_mps=%.9f dv_bits=%016" PRIx64
               " work_units=%" PRIu64 " fastest_tour=",
               G_CASES[c].name, status, (unsigned)g_solution.usable,
               (unsigned)g_solution.leg_count, g_solution.total_dv_mps,
               bits(g_solution.total_dv_mps), g_solution.work_units);
        if (g_solution.has_fastest_tour_s) {
            printf("%016" PRIx64, bits(g_solution.fastest_tour_s));
        } else {
            printf("none");
        }
        printf(" checksum=%016" PRIx64 "\n", geo_checksum(&g_solution));
    }
    return 0;
}

static void print_l(const char *name, int32_t status) {
    if (status < 0) {
        print_refusal('L', name, RECONFIG_PLANNER_LEO_ARC, status, &l_solution.error);
        return;
    }
    printf("L %s status=%" PRId32 " usable=%u impulses=%u dv_mps=%.9f dv_bits=%016" PRIx64
           " work_units=%" PRIu64 " checksum=%016" PRIx64 "\n",
           name, status, (unsigned)l_solution.usable, (unsigned)l_solution.impulses,
           l_solution.total_dv_mps, bits(l_solution.total_dv_mps), l_solution.work_units,
           leo_checksum(&l_solution));
}

static int plan_l(void) {
    size_t n = sizeof L_CASES / sizeof L_CASES[0];
    for (size_t c = 0; c < n; c++) {
        int32_t status = reconfig_leo_arc_solve(leo_workspace, &L_CASES[c].problem,
                                                &L_CASES[c].settings, &l_solution);
        print_l(L_CASES[c].name, status);
    }
    /* A setting outside its range: refused before planning, naming it. */
    ReconfigLeoArcSettings bad;
    if (reconfig_leo_arc_default_settings(&bad) != 0) return 1;
    bad.min_gap_s = -1.0;
    char name[128];
    snprintf(name, sizeof name, "%s+bad-min-gap", L_CASES[0].name);
    print_l(name, reconfig_leo_arc_solve(leo_workspace, &L_CASES[0].problem, &bad, &l_solution));
    return 0;
}

static void print_h(const char *name, int32_t status) {
    if (status < 0) {
        print_refusal('H', name, RECONFIG_PLANNER_HYBRID, status, &h_solution.error);
        return;
    }
    /* The final mass is the check flight's (0 when it was not flown: has_flown 0). */
    printf("H %s status=%" PRId32 " usable=%u iterations=%" PRIu32 " walked=%u m_f=%.9f"
           " mass_bits=%016" PRIx64 " tf_bits=%016" PRIx64 " work_units=%" PRIu64
           " checksum=%016" PRIx64 "\n",
           name, status, (unsigned)h_solution.usable, h_solution.iterations,
           (unsigned)h_solution.walked_shootings, h_solution.flown.final_mass,
           bits(h_solution.flown.final_mass), bits(h_solution.duration_tu),
           h_solution.work_units, hybrid_checksum(&h_solution));
}

static int plan_h(void) {
    size_t n = sizeof H_CASES / sizeof H_CASES[0];
    for (size_t c = 0; c < n; c++) {
        int32_t status = reconfig_hybrid_solve(hybrid_workspace, &H_CASES[c].problem,
                                               &H_CASES[c].settings, &h_solution);
        print_h(H_CASES[c].name, status);
    }
    /* An arrival point off the halo orbit: refused before planning, the miss and the
     * tolerance. */
    ReconfigHybridProblem off = H_CASES[0].problem;
    off.arrival_v_vu[1] += 1e-3;
    char name[128];
    snprintf(name, sizeof name, "%s+off-halo", H_CASES[0].name);
    print_h(name, reconfig_hybrid_solve(hybrid_workspace, &off, &H_CASES[0].settings,
                                        &h_solution));
    return 0;
}

int main(void) {
    if (reconfig_pseudospectral_workspace_size() > sizeof a_workspace ||
        reconfig_impulsive_workspace_size() > sizeof b_workspace ||
        reconfig_geo_tour_workspace_size() > sizeof geo_workspace ||
        reconfig_leo_arc_workspace_size() > sizeof leo_workspace ||
        reconfig_hybrid_workspace_size() > sizeof hybrid_workspace ||
        reconfig_pseudospectral_workspace_align() > 8 || reconfig_impulsive_workspace_align() > 8 ||
        reconfig_geo_tour_workspace_align() > 8 || reconfig_leo_arc_workspace_align() > 8 ||
        reconfig_hybrid_workspace_align() > 8) {
        fprintf(stderr,
                "workspace buffers too small: A needs %zu, B %zu, GEO %zu, LEO %zu, hybrid %zu "
                "bytes\n",
                reconfig_pseudospectral_workspace_size(), reconfig_impulsive_workspace_size(),
                reconfig_geo_tour_workspace_size(), reconfig_leo_arc_workspace_size(),
                reconfig_hybrid_workspace_size());
        return 2;
    }
    if (reconfig_pseudospectral_init(a_workspace, sizeof a_workspace) != 0) return 3;
    if (reconfig_impulsive_init(b_workspace, sizeof b_workspace) != 0) return 3;
    if (reconfig_geo_tour_init(geo_workspace, sizeof geo_workspace) != 0) return 3;
    if (reconfig_leo_arc_init(leo_workspace, sizeof leo_workspace) != 0) return 3;
    if (reconfig_hybrid_init(hybrid_workspace, sizeof hybrid_workspace) != 0) return 3;
    if (plan_a() != 0 || plan_b() != 0 || plan_f() != 0 || plan_g() != 0 || plan_l() != 0 ||
        plan_h() != 0)
        return 4;
    return 0;
}
