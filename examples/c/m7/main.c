/*
 * The C interface on the emulated Cortex-M7 (QEMU mps2-an500): a freestanding C program (no C
 * library) that plans every fixture of examples/c/fixture_data.h (planners A and B, the GEO
 * tour, the LEO arcs, the hybrid transfer) through libreconfig_capi.a
 * built for thumbv7em-none-eabihf, and prints per fixture the status, the bits of J / total
 * delta-v, the work units, the checksum of examples/c/plan_fixtures.c, and the stack the solve
 * call used (a request the built-in limits refuse prints the refusal, named, as
 * plan_fixtures.c does). Output and exit go through semihosting. The hybrid solve is
 * stack-only, about 74 KB: the 128 KiB stack of link.ld holds it. Built and run by tests/tests/c_api.rs:
 *
 *   cargo rustc -p reconfig-capi --release --target thumbv7em-none-eabihf --lib \
 *       --crate-type staticlib --no-default-features --features abort-proof
 *   clang --target=thumbv7em-none-eabihf -mcpu=cortex-m7 -mfloat-abi=hard -ffreestanding \
 *       -ffp-contract=off -O2 -I capi/include -I examples/c -I <fixture_data.h> -c main.c
 *   arm-none-eabi-ld -T examples/c/m7/link.ld --gc-sections main.o libreconfig_capi.a
 *   qemu-system-arm -cpu cortex-m7 -machine mps2-an500 -nographic \
 *       -semihosting-config enable=on,target=native -kernel image.elf
 */
#include <stddef.h>
#include <stdint.h>

#include "reconfig.h"
#include "cases.h"
#include "checksum.h"
#include "fixture_data.h"

/* ---- semihosting ---- */
static int semihost(int op, const void *arg) {
    register int r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}
static void put(const char *text) { semihost(0x04, text); }
static void __attribute__((noreturn)) exit_with(int ok) {
    /* ADP_Stopped_ApplicationExit (QEMU exits 0) or ADP_Stopped_RunTimeErrorUnknown (1). */
    semihost(0x18, (const void *)(uintptr_t)(ok ? 0x20026 : 0x20023));
    for (;;) {}
}

/* ---- line formatting (no printf without a C library) ---- */
static char line[320];
static size_t at;
static void add(const char *s) {
    while (*s && at + 1 < sizeof line) line[at++] = *s++;
    line[at] = 0;
}
static void add_hex(uint64_t v) {
    char d[17];
    for (int i = 15; i >= 0; i--) { d[i] = "0123456789abcdef"[v & 15]; v >>= 4; }
    d[16] = 0;
    add(d);
}
static void add_u(uint64_t v) {
    char d[21];
    int i = 20;
    d[i] = 0;
    do { d[--i] = (char)('0' + v % 10); v /= 10; } while (v);
    add(&d[i]);
}
static void add_i(int64_t v) {
    if (v < 0) { add("-"); add_u((uint64_t)(-v)); } else add_u((uint64_t)v);
}

/* ---- stack high-water of one call ---- */
extern uint32_t _stack_bottom;
#define PAINT 0xCCCCCCCCu
static void paint_stack(void) {
    uint32_t *p = &_stack_bottom;
    uint32_t *sp;
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    while (p < sp - 64) *p++ = PAINT;
}
static uint32_t *lowest_touched(void) {
    uint32_t *p = &_stack_bottom;
    while (*p == PAINT) p++;
    return p;
}
static uintptr_t current_sp(void) {
    uintptr_t sp;
    __asm__ volatile("mov %0, sp" : "=r"(sp));
    return sp;
}

/* A refusal's fields, as examples/c/plan_fixtures.c prints them: code, field, index, the
 * setting's name when the refusal names a setting, the bits of the value and the limit. */
static void add_refusal(int32_t planner, int32_t status, const ReconfigError *e) {
    const char *setting = 0;
    if (status == RECONFIG_ERR_SETTING_OUT_OF_RANGE || status == RECONFIG_ERR_LIMIT_EXCEEDED)
        setting = reconfig_setting_name(planner, e->index);
    add(" status="); add_i(status);
    add(" field="); add_i(e->field);
    add(" index="); add_i(e->index);
    add(" setting="); add(setting ? setting : "-");
    add(" value_bits="); add_hex(bits(e->value));
    add(" limit_bits="); add_hex(bits(e->limit));
}

/* ---- the planners, in caller memory ---- */
static uint64_t a_workspace[220000 / 8];
static uint64_t b_workspace[8192 / 8];
static ReconfigASolution a_solution;
static ReconfigBSolution b_solution;
static ReconfigBFormSolution f_solution;
static uint64_t geo_workspace[65536 / 8];
static ReconfigGeoSolution g_solution;
static uint64_t leo_workspace[32768 / 8];
static ReconfigLeoArcSolution l_solution;
static uint64_t hybrid_workspace[8192 / 8];
static ReconfigHybridSolution h_solution;

static int plan_a(void) {
    ReconfigASettings settings;
    if (reconfig_pseudospectral_default_settings(&settings) != 0) return 0;
    for (size_t c = 0; c < sizeof A_CASES / sizeof A_CASES[0]; c++) {
        paint_stack();
        uintptr_t sp = current_sp();
        int32_t status = reconfig_pseudospectral_solve(a_workspace, &A_CASES[c].problem,
                                                       &settings, &a_solution);
        uintptr_t used = sp - (uintptr_t)lowest_touched();
        uint64_t h = UINT64_C(0xcbf29ce484222325);
        for (int s = 0; s < RECONFIG_A_MAX_SPACECRAFT; s++)
            for (int n = 0; n < RECONFIG_A_MAX_NODES; n++) {
                for (int k = 0; k < 6; k++) h = mix(h, a_solution.states_lu_lutu[s][n][k]);
                for (int k = 0; k < 3; k++) h = mix(h, a_solution.controls_fu[s][n][k]);
            }
        at = 0;
        add("A "); add(A_CASES[c].name);
        if (status < 0) {
            add_refusal(RECONFIG_PLANNER_PSEUDOSPECTRAL, status, &a_solution.error);
        } else {
            add(" status="); add_i(status);
            add(" J_bits="); add_hex(bits(a_solution.cost_fu2_tu));
            add(" min_sep_bits="); add_hex(bits(a_solution.min_separation_lu));
            add(" work_units="); add_u(a_solution.work_units);
            add(" checksum="); add_hex(h);
        }
        add(" stack_bytes="); add_u(used);
        add("\n");
        put(line);
    }
    return 1;
}

static int plan_b(void) {
    ReconfigBSettings defaults;
    if (reconfig_impulsive_default_settings(&defaults) != 0) return 0;
    for (size_t c = 0; c < sizeof B_CASES / sizeof B_CASES[0]; c++) {
        ReconfigBSettings settings = defaults;
        if (B_CASES[c].fixed_point_only) {
            settings.min_fuel = 0;
            settings.nonlinear_correction = 0;
        }
        paint_stack();
        uintptr_t sp = current_sp();
        int32_t status = reconfig_impulsive_solve(b_workspace, &B_CASES[c].problem, &settings,
                                                  &b_solution);
        uintptr_t used = sp - (uintptr_t)lowest_touched();
        uint64_t h = UINT64_C(0xcbf29ce484222325);
        for (int i = 0; i < b_solution.impulse_count; i++) {
            h = mix(h, b_solution.impulses[i].time_s);
            for (int k = 0; k < 3; k++) h = mix(h, b_solution.impulses[i].dv_rtn_mps[k]);
        }
        h = mix(h, b_solution.terminal_position_error_m);
        at = 0;
        add("B "); add(B_CASES[c].name);
        if (status < 0) {
            add_refusal(RECONFIG_PLANNER_IMPULSIVE, status, &b_solution.error);
        } else {
            add(" status="); add_i(status);
            add(" dv_bits="); add_hex(bits(b_solution.total_dv_mps));
            add(" work_units="); add_u(b_solution.work_units);
            add(" checksum="); add_hex(h);
        }
        add(" stack_bytes="); add_u(used);
        add("\n");
        put(line);
    }
    return 1;
}

/* Planner B's other input forms, in the planner-B workspace. */
static int plan_f(void) {
    ReconfigBSettings defaults;
    if (reconfig_impulsive_default_settings(&defaults) != 0) return 0;
    for (size_t c = 0; c < sizeof F_CASES / sizeof F_CASES[0]; c++) {
        ReconfigBSettings settings = defaults;
        if (F_CASES[c].fixed_point_only) {
            settings.min_fuel = 0;
            settings.nonlinear_correction = 0;
        }
        paint_stack();
        uintptr_t sp = current_sp();
        int32_t status = reconfig_impulsive_solve_form(b_workspace, &F_CASES[c].problem,
                                                       &settings, &f_solution);
        uintptr_t used = sp - (uintptr_t)lowest_touched();
        const ReconfigBSolution *p = &f_solution.plan;
        uint64_t h = UINT64_C(0xcbf29ce484222325);
        for (int i = 0; i < p->impulse_count; i++) {
            h = mix(h, p->impulses[i].time_s);
            for (int k = 0; k < 3; k++) h = mix(h, p->impulses[i].dv_rtn_mps[k]);
        }
        h = mix(h, p->terminal_position_error_m);
        at = 0;
        add("F "); add(F_CASES[c].name);
        if (status < 0) {
            add_refusal(RECONFIG_PLANNER_IMPULSIVE, status, &p->error);
        } else {
            add(" status="); add_i(status);
            add(" dv_bits="); add_hex(bits(p->total_dv_mps));
            add(" work_units="); add_u(p->work_units);
            add(" checksum="); add_hex(h);
            add(" end_form="); add_u(f_solution.end.form);
            add(" end_checksum=");
            add_hex(end_checksum(UINT64_C(0xcbf29ce484222325), &f_solution.end));
        }
        add(" stack_bytes="); add_u(used);
        add("\n");
        put(line);
    }
    return 1;
}

static int plan_g(void) {
    for (size_t c = 0; c < sizeof G_CASES / sizeof G_CASES[0]; c++) {
        paint_stack();
        uintptr_t sp = current_sp();
        int32_t status = reconfig_geo_tour_solve(geo_workspace, &G_CASES[c].problem,
                                                 &G_CASES[c].settings, &g_solution);
        uintptr_t used = sp - (uintptr_t)lowest_touched();
        at = 0;
        add("G "); add(G_CASES[c].name);
        if (status < 0) {
            add_refusal(RECONFIG_PLANNER_GEO_TOUR, status, &g_solution.error);
        } else {
            add(" status="); add_i(status);
            add(" dv_bits="); add_hex(bits(g_solution.total_dv_mps));
            add(" work_units="); add_u(g_solution.work_units);
            add(" checksum="); add_hex(geo_checksum(&g_solution));
        }
        add(" stack_bytes="); add_u(used);
        add("\n");
        put(line);
    }
    return 1;
}

/* One LEO arc: `suffix` is appended to the case's name (the refusal run's). */
static void solve_l(size_t c, const ReconfigLeoArcSettings *settings, const char *suffix) {
    paint_stack();
    uintptr_t sp = current_sp();
    int32_t status = reconfig_leo_arc_solve(leo_workspace, &L_CASES[c].problem, settings,
                                            &l_solution);
    uintptr_t used = sp - (uintptr_t)lowest_touched();
    at = 0;
    add("L "); add(L_CASES[c].name); add(suffix);
    if (status < 0) {
        add_refusal(RECONFIG_PLANNER_LEO_ARC, status, &l_solution.error);
    } else {
        add(" status="); add_i(status);
        add(" dv_bits="); add_hex(bits(l_solution.total_dv_mps));
        add(" work_units="); add_u(l_solution.work_units);
        add(" checksum="); add_hex(leo_checksum(&l_solution));
    }
    add(" stack_bytes="); add_u(used);
    add("\n");
    put(line);
}

static int plan_l(void) {
    for (size_t c = 0; c < sizeof L_CASES / sizeof L_CASES[0]; c++)
        solve_l(c, &L_CASES[c].settings, "");
    /* A setting outside its range, as examples/c/plan_fixtures.c. */
    ReconfigLeoArcSettings bad;
    if (reconfig_leo_arc_default_settings(&bad) != 0) return 0;
    bad.min_gap_s = -1.0;
    solve_l(0, &bad, "+bad-min-gap");
    return 1;
}

/* One hybrid transfer: `suffix` is appended to the case's name (the refusal run's). */
static void solve_h(size_t c, const ReconfigHybridProblem *problem, const char *suffix) {
    paint_stack();
    uintptr_t sp = current_sp();
    int32_t status = reconfig_hybrid_solve(hybrid_workspace, problem, &H_CASES[c].settings,
                                           &h_solution);
    uintptr_t used = sp - (uintptr_t)lowest_touched();
    at = 0;
    add("H "); add(H_CASES[c].name); add(suffix);
    if (status < 0) {
        add_refusal(RECONFIG_PLANNER_HYBRID, status, &h_solution.error);
    } else {
        add(" status="); add_i(status);
        add(" mass_bits="); add_hex(bits(h_solution.flown.final_mass));
        add(" tf_bits="); add_hex(bits(h_solution.duration_tu));
        add(" work_units="); add_u(h_solution.work_units);
        add(" checksum="); add_hex(hybrid_checksum(&h_solution));
    }
    add(" stack_bytes="); add_u(used);
    add("\n");
    put(line);
}

static int plan_h(void) {
    for (size_t c = 0; c < sizeof H_CASES / sizeof H_CASES[0]; c++)
        solve_h(c, &H_CASES[c].problem, "");
    /* An arrival point off the halo orbit, as examples/c/plan_fixtures.c. */
    ReconfigHybridProblem off = H_CASES[0].problem;
    off.arrival_v_vu[1] += 1e-3;
    solve_h(0, &off, "+off-halo");
    return 1;
}

int main(void) {
    if (reconfig_pseudospectral_workspace_size() > sizeof a_workspace ||
        reconfig_impulsive_workspace_size() > sizeof b_workspace ||
        reconfig_geo_tour_workspace_size() > sizeof geo_workspace ||
        reconfig_leo_arc_workspace_size() > sizeof leo_workspace ||
        reconfig_hybrid_workspace_size() > sizeof hybrid_workspace) {
        at = 0;
        add("workspace buffers too small: A needs ");
        add_u(reconfig_pseudospectral_workspace_size());
        add(", B needs ");
        add_u(reconfig_impulsive_workspace_size());
        add(", GEO needs ");
        add_u(reconfig_geo_tour_workspace_size());
        add(", LEO needs ");
        add_u(reconfig_leo_arc_workspace_size());
        add(", hybrid needs ");
        add_u(reconfig_hybrid_workspace_size());
        add("\n");
        put(line);
        return 0;
    }
    if (reconfig_pseudospectral_init(a_workspace, sizeof a_workspace) != 0) return 0;
    if (reconfig_impulsive_init(b_workspace, sizeof b_workspace) != 0) return 0;
    if (reconfig_geo_tour_init(geo_workspace, sizeof geo_workspace) != 0) return 0;
    if (reconfig_leo_arc_init(leo_workspace, sizeof leo_workspace) != 0) return 0;
    if (reconfig_hybrid_init(hybrid_workspace, sizeof hybrid_workspace) != 0) return 0;
    at = 0;
    add("workspace_bytes A="); add_u(reconfig_pseudospectral_workspace_size());
    add(" B="); add_u(reconfig_impulsive_workspace_size());
    add(" GEO="); add_u(reconfig_geo_tour_workspace_size());
    add(" LEO="); add_u(reconfig_leo_arc_workspace_size());
    add(" HYBRID="); add_u(reconfig_hybrid_workspace_size());
    add("\n");
    put(line);
    return plan_a() && plan_b() && plan_f() && plan_g() && plan_l() && plan_h();
}

/* The abort-free proof (docs/c-api.md, "Abort-free"): the library's panic handler calls
 * reconfig_capi_panic_path_survived_optimisation(), which this program does NOT define. The
 * image links only because no panic path of the library survives optimisation; a change that
 * brings one back fails this link (tests/tests/c_api.rs). */

/* ---- start-up: FPU on, .data and .bss, main, exit ---- */
extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _stack_top;
void reset_handler(void) __attribute__((noreturn));
void fault_handler(void) {
    put("FAULT\n");
    exit_with(0);
}
void reset_handler(void) {
    /* CP10 and CP11 full access (the double-precision FPU), before any FP instruction. */
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
    __asm__ volatile("dsb\n isb" ::: "memory");
    for (uint32_t *s = &_sidata, *d = &_sdata; d < &_edata;) *d++ = *s++;
    for (uint32_t *d = &_sbss; d < &_ebss;) *d++ = 0;
    exit_with(main());
}

__attribute__((section(".vectors"), used)) static void (*const vectors[16])(void) = {
    (void (*)(void))(&_stack_top), reset_handler, fault_handler, fault_handler,
    fault_handler, fault_handler, fault_handler, 0, 0, 0, 0,
    fault_handler, fault_handler, 0, fault_handler, fault_handler,
};
