//! The per-arc search's coarse grid of the first impulse epoch: at each grid epoch the
//! two-impulse J2-corrected Lambert transfers over the revolution counts near the clients' own
//! (both branches), and for three or more impulses a plane seed; the best distinct candidates
//! are where the compass search ([`super::arc`]) starts.

use super::arc::{families, period_s, Client, Ctx, Point};
use super::j2::{join, pos, vel, State};
use super::shoot::{corrected_lambert, metered_lambert, Family, Offset, Secant};
use super::types::{Settings, MAX_CANDIDATES, MAX_VARS};
use super::work_units;
use crate::indexed::IndexedExt as _;
use crate::lambert::{self, Branch};
use crate::vec3::{add, cross, dot, norm, scale, sub, Vec3};

/// The families of a plane seed whose first leg leaves at the grid point of the two-impulse
/// family `best`: its last leg is shorter by up to a revolution, so two revolutions fewer to one
/// more than `best` (both branches). Measured: the same plans on Examples I and II and the
/// same sequencing as all the families, for a fifth less time of the sequencing.
fn near_families(settings: &Settings, best: Family) -> impl Iterator<Item = Family> {
    let lo = best.revs.saturating_sub(2);
    let hi = best.revs.saturating_add(1).min(settings.max_revolutions);
    families(settings.max_revolutions).filter(move |f| (lo..=hi).contains(&f.revs))
}

/// Whole revolutions beyond the clients' own that a grid transfer may make: its families are
/// those whose revolution count lies within this many of the counts of the two clients' orbits
/// over the transfer's time. A K-revolution transfer over `tof` has a period near `tof / K`, so
/// its semi-major axis leaves the clients' band as K leaves their counts, and its phasing Δv
/// grows with that distance. Measured (`cargo run --release -p reconfig-host --example
/// leo_onboard`): 2 keeps every plan of Examples I and II and the sequencing bit for bit (1
/// keeps their Δv but not their evaluations), for 30 % less time of the sequencing than all
/// 81 families.
const GRID_REVOLUTION_WINDOW: f64 = 2.0;

/// The families a grid transfer from `from` to the arrival `to` in `tof_s` tries (see
/// [`GRID_REVOLUTION_WINDOW`]).
#[derive(Clone, Copy, Debug)]
struct RevolutionWindow {
    lo: f64,
    hi: f64,
}

impl RevolutionWindow {
    fn contains(&self, f: &Family) -> bool {
        let k = f64::from(f.revs);
        self.lo <= k && k <= self.hi
    }
}

fn revolution_window(mu: f64, from: &State, to: &State, tof_s: f64) -> RevolutionWindow {
    let (pa, pb) = (period_s(mu, from), period_s(mu, to));
    // A client on an escape orbit (period 0) gives no count: every family.
    if !(pa > 0.0 && pb > 0.0) {
        return RevolutionWindow {
            lo: 0.0,
            hi: f64::INFINITY,
        };
    }
    let (ka, kb) = (tof_s / pa, tof_s / pb);
    RevolutionWindow {
        lo: ka.min(kb) - GRID_REVOLUTION_WINDOW,
        hi: ka.max(kb) + GRID_REVOLUTION_WINDOW,
    }
}

impl Ctx<'_> {
    /// The offset estimated from the client's own orbit: where two-body and J2 flights of the
    /// client from `t_s` to the arrival differ (the transfer ends on that orbit).
    pub(crate) fn client_offset(&mut self, t_s: f64) -> Option<Offset> {
        let sb = self.client_state(Client::B, t_s)?;
        if !self.meter.spend(work_units::two_body_propagation()) {
            return None;
        }
        let (r, v) = lambert::propagate(
            self.settings.mu_km3_s2,
            &pos(&sb),
            &vel(&sb),
            self.tf - t_s,
            work_units::TWO_BODY_MAX_ITER,
        )?;
        Some(Offset {
            dr_km: sub(&r, &pos(&self.b_end)),
            dv_km_s: sub(&vel(&self.b_end), &v),
        })
    }

    /// Coarse grid of the first epoch with two-impulse transfers: the best distinct
    /// candidates, cheapest first, written into `out` (emptied first).
    pub fn grid(&mut self, out: &mut [Option<Point>; MAX_CANDIDATES]) {
        *out = [None; MAX_CANDIDATES];
        let keep = usize::from(self.settings.candidates).min(MAX_CANDIDATES);
        let span = self.tf - self.settings.min_gap_s;
        let g = f64::from(self.settings.grid_points);
        let spacing = span / g;
        // Every family is scanned against the window at each epoch.
        let scanned = families(self.settings.max_revolutions).count() as u64;
        let epoch_units =
            work_units::GRID_POINT.saturating_add(scanned.saturating_mul(work_units::GRID_FAMILY));
        for j in 0..self.settings.grid_points {
            if !self.meter.spend(epoch_units) {
                return;
            }
            let t1 = f64::from(j) * spacing;
            let Some(sa) = self.client_state(Client::A, t1) else {
                break;
            };
            let Some(off) = self.client_offset(t1) else {
                continue;
            };
            let tof = self.tf - t1;
            let mut cheapest: Option<(Family, f64)> = None;
            let window = revolution_window(self.settings.mu_km3_s2, &sa, &self.b_end, tof);
            for fam in families(self.settings.max_revolutions).filter(|f| window.contains(f)) {
                let Some((v_dep, v_arr)) = corrected_lambert(
                    self.settings,
                    &sa,
                    &pos(&self.b_end),
                    tof,
                    fam,
                    &off,
                    &mut self.meter,
                ) else {
                    if self.meter.stage_refused() {
                        return;
                    }
                    continue;
                };
                let dv1 = sub(&v_dep, &vel(&sa));
                let c = norm(&dv1) + norm(&sub(&vel(&self.b_end), &v_arr));
                if !c.is_finite() {
                    continue;
                }
                if cheapest.is_none_or(|(_, b)| c < b) {
                    cheapest = Some((fam, c));
                }
                if !self.meter.spend(work_units::GRID_INSERT) {
                    return;
                }
                let p = self.initial_point(t1, &sa, dv1, fam, off, c);
                insert(out, keep, p, 1.5 * spacing);
            }
            if self.impulses > 2 {
                if let Some(p) = self.plane_seed(t1, &sa, cheapest.map(|(f, _)| f)) {
                    if !self.meter.spend(work_units::GRID_INSERT) {
                        return;
                    }
                    insert(out, keep, p, 1.5 * spacing);
                }
                if let Some(p) = self.node_seed(t1, cheapest.map(|(f, _)| f)) {
                    if !self.meter.spend(work_units::GRID_INSERT) {
                        return;
                    }
                    insert(out, keep, p, 1.5 * spacing);
                }
            }
        }
    }

    /// A three-or-more-impulse seed at `t1`: a half-revolution leg to the point of the
    /// client's plane opposite the chaser (at the client's radius), so the last leg lies in
    /// the client's plane and the plane change is made by the first two impulses; the last
    /// leg's family the cheapest of those near `near` (the grid point's cheapest two-impulse
    /// family, see [`near_families`]), of all when there is none.
    fn plane_seed(&mut self, t1: f64, sa: &State, near: Option<Family>) -> Option<Point> {
        let sb = self.client_state(Client::B, t1)?;
        let hb = cross(&pos(&sb), &vel(&sb));
        let hb = scale(&hb, 1.0 / norm(&hb));
        let ra = pos(sa);
        let back = scale(&ra, -1.0);
        let d = sub(&back, &scale(&hb, dot(&back, &hb)));
        let rb = norm(&pos(&sb));
        let rm = scale(&d, rb / norm(&d));
        let at = 0.5 * (norm(&ra) + rb);
        let mu = self.settings.mu_km3_s2;
        let tof = core::f64::consts::PI * libm::sqrt(at * at * at / mu);
        let normal = cross(&ra, &vel(sa));
        let direct = Family {
            revs: 0,
            branch: Branch::Left,
        };
        let leg = metered_lambert(
            self.settings,
            (&ra, &rm, tof),
            direct,
            &normal,
            None,
            &mut self.meter,
        )?;
        let dv1 = sub(&leg.v1_km_s, &vel(sa));
        let mut x = [0.0; MAX_VARS];
        let free = self.impulses.saturating_sub(1);
        let room = self.tf - self.settings.min_gap_s - t1;
        let step = tof.min(room / (free as f64)).max(0.0);
        for (k, xi) in x.iter_mut().take(free).indexed() {
            *xi = t1 + ((k as f64) * step).min(tof);
        }
        self.seed_point(x, &dv1, t1 + step, near)
    }

    /// A seed of the grid (plane or node seed) as a point: `x` with its free epochs set, the
    /// first free impulse `dv1`, the last leg's offset estimated from the client's orbit from
    /// `t2` (the second impulse), its family the cheapest of those near `near` (the grid
    /// point's cheapest two-impulse family, see [`near_families`]), of all when `None`.
    pub(super) fn seed_point(
        &mut self,
        mut x: [f64; MAX_VARS],
        dv1: &Vec3,
        t2: f64,
        near: Option<Family>,
    ) -> Option<Point> {
        let free = self.impulses.saturating_sub(1);
        for (xi, d) in x.iter_mut().skip(free).zip(dv1.iter()) {
            *xi = *d;
        }
        let off = self.client_offset(t2)?;
        let (fam, cost) = match near {
            Some(f) => self.best_family_of(&x, &off, near_families(self.settings, f))?,
            None => self.best_family(&x, &off)?,
        };
        Some(Point {
            x,
            fam,
            off,
            cost,
            shot: false,
            secant: Secant::default(),
        })
    }

    /// A grid point as a point of the M-impulse variables: the intermediate impulses start at
    /// zero, spread over the first revolution of the transfer.
    fn initial_point(
        &self,
        t1: f64,
        sa: &State,
        dv1: Vec3,
        fam: Family,
        off: Offset,
        cost: f64,
    ) -> Point {
        let mut x = [0.0; MAX_VARS];
        let after = join(&pos(sa), &add(&vel(sa), &dv1));
        let period = period_s(self.settings.mu_km3_s2, &after);
        let free = self.impulses.saturating_sub(1);
        let room = self.tf - self.settings.min_gap_s - t1;
        let step = (0.5 * period).min(room / (free as f64)).max(0.0);
        for (k, xi) in x.iter_mut().take(free).indexed() {
            *xi = t1 + (k as f64) * step;
        }
        // The first free vector is the transfer's departure burn; the others start at zero.
        if self.impulses > 2 {
            for (xi, d) in x.iter_mut().skip(free).zip(dv1.iter()) {
                *xi = *d;
            }
        }
        Point {
            x,
            fam,
            off,
            cost,
            shot: false,
            secant: Secant::default(),
        }
    }
}

/// Insert `p` into the sorted list of the `keep` cheapest, one per family and neighbourhood
/// of the first epoch (`near_s`).
fn insert(out: &mut [Option<Point>; MAX_CANDIDATES], keep: usize, p: Point, near_s: f64) {
    let t1 = p.x[0];
    let same = out
        .iter()
        .index_of(|q| q.is_some_and(|q| q.fam == p.fam && (q.x[0] - t1).abs() <= near_s));
    if let Some(i) = same {
        if let Some(slot) = out.get_mut(i) {
            if slot.is_some_and(|q| p.cost < q.cost) {
                *slot = Some(p);
            }
        }
    } else if let Some(slot) = out.get_mut(keep.saturating_sub(1)) {
        if slot.is_none_or(|q| p.cost < q.cost) {
            *slot = Some(p);
        }
    }
    // Keep the list sorted (cheapest first, empty slots last): insertion sort on the 8 entries.
    out.sort_unstable_by(|a, b| match (a, b) {
        (Some(a), Some(b)) => a.cost.total_cmp(&b.cost),
        (Some(_), None) => core::cmp::Ordering::Less,
        (None, Some(_)) => core::cmp::Ordering::Greater,
        (None, None) => core::cmp::Ordering::Equal,
    });
}
