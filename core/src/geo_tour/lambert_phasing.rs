//! Lambert phasing: the servicer leaves its slot on the Lambert arc that reaches the client's
//! position `tau` later with K whole revolutions, and matches the client's velocity there.
//! Two burns: `v1 - v_slot` and `v_client - v2`.
//!
//! ## Wells
//! Seen as a function of `tau`, the cost has one well per revolution. The end points coincide
//! when `s du + n0 tau = 2 pi m` (`tau_m = (2 pi m - s du) / n0`, m >= 1): there Lambert's
//! problem degenerates (`lambda = 1`) and its tangential branch is the m-revolution phasing
//! orbit (for m = 1, the one-revolution Hohmann-type method). The cost is continuous through
//! `tau_m` (the (m-1)-revolution family before, the m-revolution family after) and its minimum
//! lies just before it, on the (m-1)-revolution family whose transfer angle approaches 2 pi
//! (e.g. 0.12 deg: 0.683 m/s 20 min before `tau_1`, 0.689 m/s 20 min after; a time price only
//! moves the optimum earlier). Exactly at `tau_m` the geometry is degenerate and the solver's
//! answer is not used. So well m is searched before `tau_m` with K = m - 1, both branches, by
//! golden section (`well_iterations` steps, each 1 or 2 Lambert solves), on the family's basin
//! ([`well_window_s`]).

use super::geo::{inertial_to_rtn, Geo};
use super::maneuver::{Burn, Direction, Maneuver, Method};
use super::work_units::{self, Gauge};
use crate::astro::{M_PER_KM, TWO_PI};
use crate::indexed::IndexedExt as _;
use crate::lambert::{self, Branch, LambertSolution};

/// Lambert solver bounds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LambertBounds {
    pub max_iter: u16,
    pub tol: f64,
}

/// The two burns of the K-revolution arc of duration `tau_s` on `branch`, inertial frame
/// at the departure slot (longitude 0 at epoch 0, by symmetry of the ring), with its cost and
/// Izzo's x (a warm start for a nearby arc of the same family, `guess`): `None` if the family
/// has no solution for this time. The arc takes `LAMBERT_ARC` from `gauge` first and each of
/// the solver's steps its step's units; when one is refused the arc is `None`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn arc(
    g: &Geo,
    dir: Direction,
    phase_rad: f64,
    tau_s: f64,
    revs: u16,
    branch: Branch,
    b: LambertBounds,
    guess: Option<f64>,
    gauge: &mut Gauge<'_>,
) -> Option<(Maneuver, f64, f64)> {
    if !gauge.take(work_units::LAMBERT_ARC) {
        return None;
    }
    let step_units = work_units::lambert_step(revs);
    let (r1, v1c) = g.slot_state(0.0, 0.0);
    let (r2, v2c) = g.slot_state(dir.sign() * phase_rad, tau_s);
    let sol: LambertSolution = lambert::solve_from_stepped(
        g.mu,
        &r1,
        &r2,
        tau_s,
        revs,
        branch,
        &[0.0, 0.0, 1.0],
        (b.max_iter, b.tol),
        guess,
        &mut || gauge.take(step_units),
    )
    .ok()?;
    let d1 = [
        sol.v1_km_s[0] - v1c[0],
        sol.v1_km_s[1] - v1c[1],
        sol.v1_km_s[2] - v1c[2],
    ];
    let d2 = [
        v2c[0] - sol.v2_km_s[0],
        v2c[1] - sol.v2_km_s[1],
        v2c[2] - sol.v2_km_s[2],
    ];
    let k = |a: [f64; 3]| [a[0] * M_PER_KM, a[1] * M_PER_KM, a[2] * M_PER_KM];
    let burns = [
        Burn {
            offset_s: 0.0,
            dv_rtn_mps: k(inertial_to_rtn(&r1, &v1c, &d1)),
        },
        Burn {
            offset_s: tau_s,
            dv_rtn_mps: k(inertial_to_rtn(&r2, &v2c, &d2)),
        },
    ];
    let v = sol.v1_km_s;
    let energy = 0.5 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) - g.mu / g.a0;
    let sma = -g.mu / (2.0 * energy);
    let m = Maneuver::from_burns(Method::Lambert, tau_s, sma, revs, &burns);
    let dv = m.dv_mps;
    dv.is_finite().then_some((m, dv, sol.x))
}

/// Cheapest Lambert phasing of duration `tau_s` with exactly `revs` revolutions (both branches
/// when `revs >= 1`) whose burns are all within `cap_mps`, its arcs metered by `gauge`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn lambert_revs(
    g: &Geo,
    dir: Direction,
    phase_rad: f64,
    tau_s: f64,
    revs: u16,
    cap_mps: f64,
    b: LambertBounds,
    gauge: &mut Gauge<'_>,
) -> Option<Maneuver> {
    let mut best: Option<Maneuver> = None;
    let branches: &[Branch] = if revs == 0 {
        &[Branch::Left]
    } else {
        &[Branch::Left, Branch::Right]
    };
    for &br in branches {
        if let Some((m, dv, _)) = arc(g, dir, phase_rad, tau_s, revs, br, b, None, gauge) {
            let better = best.as_ref().is_none_or(|x| dv < x.dv_mps);
            if m.max_burn_mps <= cap_mps && better {
                best = Some(m);
            }
        }
    }
    best
}

/// Cheapest Lambert phasing of duration `tau_s` over every revolution count `0..=max_revs`
/// and both branches, burns within `cap_mps` (the "every branch" evaluation).
#[allow(clippy::too_many_arguments)]
pub fn lambert_phasing(
    g: &Geo,
    dir: Direction,
    phase_rad: f64,
    tau_s: f64,
    max_revs: u16,
    cap_mps: f64,
    max_iter: u16,
    tol: f64,
) -> Option<Maneuver> {
    let b = LambertBounds { max_iter, tol };
    let mut best: Option<Maneuver> = None;
    for k in 0..=max_revs {
        if let Some(m) = lambert_revs(g, dir, phase_rad, tau_s, k, cap_mps, b, &mut Gauge::paid()) {
            if best.as_ref().is_none_or(|x| m.dv_mps < x.dv_mps) {
                best = Some(m);
            }
        }
    }
    best
}

/// Time at which the end points of well `m` (>= 1) coincide, s.
pub(crate) fn coincidence_s(g: &Geo, dir: Direction, phase_rad: f64, m: u16) -> f64 {
    (TWO_PI * f64::from(m) - dir.sign() * phase_rad) / g.n0
}

/// The window well `m` is searched on: its family's basin before `tau_m`, where
/// `dv + price tau` is unimodal for every price >= 0. Well 1 (the direct family) falls all the
/// way from `tau` near 0 to its bottom: `[60 s, tau_1)`. Well m >= 2 (K = m - 1) rises from
/// well m - 1's end at `tau_{m-1}` to a peak about 0.58 T0 before `tau_m` (0.05-10 deg, K =
/// 1-2, sampled), then falls to its bottom: `[tau_m - T0/2, tau_m)`. A price moves the best
/// time earlier, so the whole basin is searched, not only the bottom's neighbourhood (the
/// T0/4 window before issue 31 kept two Lambert legs sharing 1.5 days at 0.7478 d, the
/// window's start, for 1.2891 m/s where 1.2735 fits).
pub(crate) fn well_window_s(g: &Geo, dir: Direction, phase_rad: f64, m: u16) -> (f64, f64) {
    let hi = coincidence_s(g, dir, phase_rad, m) - g.t0 * 1e-9;
    let span = if m <= 1 { g.t0 } else { 0.5 * g.t0 };
    ((hi - span).max(WELL_WINDOW_FIRST_S), hi)
}

/// The earliest transfer time a well is searched at, s (a direct arc that fast costs km/s).
const WELL_WINDOW_FIRST_S: f64 = 60.0;

/// The earliest duration any well of the leg up to well `max_well` is searched at, counting
/// only the wells not skipped outright under `cap_mps` (the windows move one period later per
/// well, so the first such well's window starts first), s; infinite when every well is
/// skipped.
pub(crate) fn wells_earliest_s(
    g: &Geo,
    dir: Direction,
    phase_rad: f64,
    max_well: u16,
    cap_mps: f64,
) -> f64 {
    (1..=max_well)
        .find(|&m| !well_skipped(g, dir, phase_rad, m, cap_mps))
        .map_or(f64::INFINITY, |m| well_window_s(g, dir, phase_rad, m).0)
}

/// Whether well `m` is skipped outright: the tangential m-revolution phasing orbit at its end
/// (which the bottom undercuts by about 1 %) needs burns above 1.25 times the cap.
pub(crate) fn well_skipped(g: &Geo, dir: Direction, phase_rad: f64, m: u16, cap_mps: f64) -> bool {
    let tau_m = coincidence_s(g, dir, phase_rad, m);
    let period = tau_m / f64::from(m.max(1));
    let a_m = libm::cbrt(g.mu * (period / TWO_PI) * (period / TWO_PI));
    let tangential_mps = (g.vis_viva(g.a0, a_m) - g.v0).abs() * M_PER_KM;
    tangential_mps.is_nan() || tangential_mps > 1.25 * cap_mps
}

/// The golden section's score of an arc whose burns break the cap, before its excess over the
/// cap is added: above any admissible arc's `dv + price * tau` (m/s; a tour's legs cost tens).
const INADMISSIBLE_SCORE: f64 = 1e9;

/// Minimise `dv(tau) + price * tau` over well `m` (K = m - 1 revolutions, `tau` in
/// [`well_window_s`]) by golden section, `iterations` steps; burns
/// within `cap_mps`. Returns the best manoeuvre found (cap-violating or failed points are
/// skipped, so the result is always admissible).
///
/// Two economies, both conservative: the well is skipped when the tangential m-revolution
/// phasing orbit at its end (which the bottom undercuts by about 1 %) needs burns above
/// 1.25 times the cap; and the branch (for K >= 1) is chosen once, the cheaper at the window's
/// two first golden points, since one branch is the near-tangential family across the whole
/// window and the other the near-rectilinear one (tens to thousands of m/s dearer).
///
/// Every arc is metered by `gauge`; when one is refused the section stops (the caller sees
/// `gauge.stopped()` and discards the result).
#[allow(clippy::too_many_arguments)]
pub(crate) fn well_minimum(
    g: &Geo,
    dir: Direction,
    phase_rad: f64,
    m: u16,
    price: f64,
    cap_mps: f64,
    iterations: u16,
    b: LambertBounds,
    gauge: &mut Gauge<'_>,
) -> Option<Maneuver> {
    let revs = m.saturating_sub(1);
    if well_skipped(g, dir, phase_rad, m, cap_mps) {
        return None;
    }
    let (lo0, hi0) = well_window_s(g, dir, phase_rad, m);
    if hi0.is_nan() || hi0 <= lo0 {
        return None;
    }
    let r = 0.5 * (libm::sqrt(5.0) - 1.0);
    let (mut lo, mut hi) = (lo0, hi0);
    let mut c = hi - r * (hi - lo);
    let mut d = lo + r * (hi - lo);
    // Score, admissible manoeuvre, and Izzo's x of the arc (kept even when the arc breaks
    // the cap: it still warm-starts the neighbouring solve). An arc that breaks the cap scores
    // above every admissible one, by how far it breaks it: the section then closes on the
    // cap-admissible part of the window (around the well's bottom, where the burns are
    // smallest) wherever its first points fall; with every such arc scored alike (infinite)
    // it closed on the window's near end, and a well whose bottom is admissible was lost.
    type Scored = (f64, Option<Maneuver>, Option<f64>);
    let score_arc = |t: f64, a: Option<(Maneuver, f64, f64)>| -> Scored {
        match a {
            Some((mv, dv, x)) if mv.max_burn_mps <= cap_mps => (dv + price * t, Some(mv), Some(x)),
            Some((mv, _, x)) => {
                let excess_mps = mv.max_burn_mps - cap_mps;
                let score = if excess_mps.is_finite() {
                    INADMISSIBLE_SCORE + excess_mps
                } else {
                    f64::INFINITY
                };
                (score, None, Some(x))
            }
            None => (f64::INFINITY, None, None),
        }
    };
    // The two first golden points, on the branch chosen there (the arcs of the chosen branch
    // are the section's first two evaluations).
    let mut at = |t: f64, br: Branch| arc(g, dir, phase_rad, t, revs, br, b, None, gauge);
    let (branch, (mut fc, mut mc, mut xc), (mut fd, mut md, mut xd)) = if revs == 0 {
        let left = Branch::Left;
        let (ac, ad) = (at(c, left), at(d, left));
        (left, score_arc(c, ac), score_arc(d, ad))
    } else {
        let arcs = [
            (Branch::Left, at(c, Branch::Left), at(d, Branch::Left)),
            (Branch::Right, at(c, Branch::Right), at(d, Branch::Right)),
        ];
        // Cheapest single arc over both points, as the branch choice always was (Left on
        // ties and when nothing solves).
        let mut best = (f64::INFINITY, 0usize);
        for point in 0..2 {
            for (i, (_, ac, ad)) in arcs.iter().indexed() {
                let a = if point == 0 { ac } else { ad };
                if let Some((_, dv, _)) = a {
                    if *dv < best.0 {
                        best = (*dv, i);
                    }
                }
            }
        }
        let [l, rr] = arcs;
        let (br, ac, ad) = if best.1 == 0 { l } else { rr };
        (br, score_arc(c, ac), score_arc(d, ad))
    };
    // Later points start Lambert's iteration from the x of the interior point the section
    // keeps, the nearest solved arc of the same family (`lambert::solve_from`: the same root
    // to the tolerance, about half the Householder steps).
    if gauge.stopped() {
        return None;
    }
    let mut best: Option<(f64, Maneuver)> = None;
    let keep = |f: f64, m: &Option<Maneuver>, best: &mut Option<(f64, Maneuver)>| {
        if let Some(mv) = m {
            if best.as_ref().is_none_or(|(bf, _)| f < *bf) {
                *best = Some((f, mv.clone()));
            }
        }
    };
    keep(fc, &mc, &mut best);
    keep(fd, &md, &mut best);
    for _ in 0..iterations {
        if fc <= fd {
            hi = d;
            d = c;
            fd = fc;
            md = mc;
            xd = xc;
            c = hi - r * (hi - lo);
            (fc, mc, xc) = score_arc(c, arc(g, dir, phase_rad, c, revs, branch, b, xd, gauge));
            if gauge.stopped() {
                return None;
            }
            keep(fc, &mc, &mut best);
        } else {
            lo = c;
            c = d;
            fc = fd;
            mc = md;
            xc = xd;
            d = lo + r * (hi - lo);
            (fd, md, xd) = score_arc(d, arc(g, dir, phase_rad, d, revs, branch, b, xc, gauge));
            if gauge.stopped() {
                return None;
            }
            keep(fd, &md, &mut best);
        }
    }
    best.map(|(_, m)| m)
}

#[cfg(test)]
mod tests {
    use super::*;

    const DEG: f64 = core::f64::consts::PI / 180.0;

    #[test]
    fn digest_reference_values_at_9_and_12_hours() {
        let g = Geo::standard();
        // Digest: 0.05..0.25 deg cost 2.15..10.75 m/s at 9 h and 1.33..6.67 m/s at 12 h.
        for (k, du) in [0.05, 0.10, 0.15, 0.20, 0.25].iter().enumerate() {
            let a = lambert_phasing(
                &g,
                Direction::East,
                du * DEG,
                9.0 * 3600.0,
                0,
                1e9,
                40,
                1e-13,
            )
            .unwrap();
            let b = lambert_phasing(
                &g,
                Direction::East,
                du * DEG,
                12.0 * 3600.0,
                0,
                1e9,
                40,
                1e-13,
            )
            .unwrap();
            let want9 = [2.15, 4.30, 6.45, 8.60, 10.75][k];
            let want12 = [1.33, 2.67, 4.00, 5.33, 6.67][k];
            assert!((a.dv_mps - want9).abs() < 0.01, "{du}: {}", a.dv_mps);
            assert!((b.dv_mps - want12).abs() < 0.01, "{du}: {}", b.dv_mps);
        }
    }

    #[test]
    fn well_bottom_is_below_the_k_revolution_phasing_orbit() {
        let g = Geo::standard();
        let b = LambertBounds {
            max_iter: 40,
            tol: 1e-13,
        };
        for dir in [Direction::East, Direction::West] {
            for m in 1..=3u16 {
                let du = 0.5 * DEG;
                let w = well_minimum(&g, dir, du, m, 0.0, 1e9, 40, b, &mut Gauge::paid()).unwrap();
                // m-revolution tangential phasing orbit: period (2 pi m - s du) / (m n0).
                let tm = coincidence_s(&g, dir, du, m) / f64::from(m);
                let am = libm::cbrt(g.mu * (tm / TWO_PI) * (tm / TWO_PI));
                let tangential = 2.0 * (g.vis_viva(g.a0, am) - g.v0).abs() * M_PER_KM;
                assert!(
                    w.dv_mps <= tangential + 1e-6,
                    "{m}: {} {}",
                    w.dv_mps,
                    tangential
                );
                assert!(
                    w.dv_mps > 0.9 * tangential,
                    "{m}: {} {}",
                    w.dv_mps,
                    tangential
                );
            }
        }
    }
}
