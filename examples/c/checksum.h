/* The checksums examples/c prints per answer, shared by the host example (plan_fixtures.c) and
 * the Cortex-M7 image (m7/main.c); tests/tests/c_api.rs computes the same over the Rust
 * answers. Freestanding: stdint.h, reconfig.h and a compiler builtin only. */
#ifndef RECONFIG_EXAMPLE_CHECKSUM_H
#define RECONFIG_EXAMPLE_CHECKSUM_H

#include <stdint.h>

#include "reconfig.h"

/* The bits of a double. */
static inline uint64_t bits(double x) {
    uint64_t b;
    __builtin_memcpy(&b, &x, sizeof b);
    return b;
}

/* FNV-style mix of 64-bit words. */
static inline uint64_t mix(uint64_t h, double x) {
    return (h ^ bits(x)) * UINT64_C(0x100000001b3);
}

/* Checksum over the numbers of the end state's member its form names (the test computes the
 * same over the Rust API's EndState). */
static inline uint64_t end_checksum(uint64_t h, const ReconfigBEndState *e) {
    const double *v = 0;
    int n = 6;
    switch (e->form) {
    case RECONFIG_B_END_ELEMENTS: v = &e->elements.dsma_km; break;
    case RECONFIG_B_END_ROE: v = &e->roe.da_m; break;
    case RECONFIG_B_END_DEPUTY_CLASSICAL: v = &e->classical.sma_km; break;
    case RECONFIG_B_END_DEPUTY_EQUINOCTIAL: v = &e->equinoctial.sma_km; break;
    case RECONFIG_B_END_DEPUTY_STATE: v = &e->state.pos_km[0]; break;
    default: n = 0; break;
    }
    for (int k = 0; k < n; k++) h = mix(h, v[k]);
    return h;
}

/* Checksum over a GEO tour's legs (start, duration, delta-v, every burn's offset and
 * components) and its mission time; the test computes the same over the Rust solution. */
static inline uint64_t geo_checksum(const ReconfigGeoSolution *g) {
    uint64_t h = UINT64_C(0xcbf29ce484222325);
    for (int l = 0; l < g->leg_count; l++) {
        const ReconfigGeoLeg *leg = &g->legs[l];
        h = mix(h, leg->start_s);
        h = mix(h, leg->duration_s);
        h = mix(h, leg->dv_mps);
        for (int b = 0; b < leg->burn_count; b++) {
            h = mix(h, leg->burns[b].offset_s);
            for (int k = 0; k < 3; k++) h = mix(h, leg->burns[b].dv_rtn_mps[k]);
        }
    }
    return mix(h, g->mission_time_s);
}

/* Checksum over a LEO arc's burns (epoch, RTN and inertial components), its miss and lowest
 * altitude (0 when absent); the test computes the same over the Rust solution. */
static inline uint64_t leo_checksum(const ReconfigLeoArcSolution *l) {
    uint64_t h = UINT64_C(0xcbf29ce484222325);
    for (int b = 0; b < l->impulses; b++) {
        h = mix(h, l->burns[b].epoch_s);
        for (int k = 0; k < 3; k++) h = mix(h, l->burns[b].dv_rtn_mps[k]);
        for (int k = 0; k < 3; k++) h = mix(h, l->burns[b].dv_km_s[k]);
    }
    h = mix(h, l->miss_m);
    return mix(h, l->lowest_altitude_km);
}

/* Checksum over a hybrid transfer's numbers: kappa, theta, the time of flight, the costates,
 * lambda0, the mass after the impulse, the residual and the walk's reach, then the check flight's
 * final mass, end miss, Hamiltonian drift and every switch-time slot (0 when absent); the test
 * computes the same over the Rust solution. */
static inline uint64_t hybrid_checksum(const ReconfigHybridSolution *s) {
    uint64_t h = UINT64_C(0xcbf29ce484222325);
    h = mix(h, s->kappa);
    h = mix(h, s->theta_rad);
    h = mix(h, s->duration_tu);
    for (int k = 0; k < RECONFIG_HYBRID_STATE_LEN; k++) h = mix(h, s->costates[k]);
    h = mix(h, s->cost_multiplier);
    h = mix(h, s->mass_after_impulse);
    h = mix(h, s->residual);
    h = mix(h, s->walked_reached);
    h = mix(h, s->flown.final_mass);
    h = mix(h, s->flown.end_miss);
    h = mix(h, s->flown.hamiltonian_drift);
    for (int k = 0; k < RECONFIG_HYBRID_MAX_SWITCH_TIMES; k++)
        h = mix(h, s->flown.switch_times_tu[k]);
    return h;
}

#endif
