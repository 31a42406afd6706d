//! One assignment's time re-allocated: its drifts by their price, then, where that does not
//! fit or pay, its Lambert wells moved with the drifts by one price. Called by the gap
//! enumeration ([`super::allocate`]) and the exchange search ([`super::exchange`]).

use super::drift_time::drift_allocate;
use super::pick::{totals, Pick};
use super::table::LegTable;
use super::types::Settings;
use super::well_price::{dv_floor_mps, has_well_leg, wells_allocate};
use super::work_units::Cut;
use crate::work::Meter;

/// Re-allocate the time of the assignment `picks`: its drift legs' by their price
/// ([`drift_allocate`]); when that cannot fit the mission time (or, with
/// `well_searches.retry_fitting`, does not beat `best_dv`) and the assignment has a leg on a
/// Lambert well, its wells and drifts moved by one price ([`wells_allocate`]), unless it cannot
/// beat `best_dv` however they move (`dv_floor_mps`) or `well_searches` (the caller's allowance
/// of such searches, each dear: a golden section per well leg per step) is spent.
/// The price, or `None` when the assignment cannot fit (or cannot beat `best_dv`); [`Cut`] as
/// the two re-allocations.
#[allow(clippy::too_many_arguments)]
pub(super) fn reallocate(
    tables: &[LegTable],
    picks: &mut [Pick],
    budget_s: f64,
    s: &Settings,
    iterations: &mut u32,
    hint: Option<f64>,
    (best_dv, well_searches): (f64, &mut WellSearches),
    meter: &mut Meter,
) -> Result<Option<f64>, Cut> {
    if let Some(price) = drift_allocate(tables, picks, budget_s, s, iterations, hint, meter)? {
        // Kept when it beats `best_dv`; else its wells may still be where another price left
        // them (a drift leg just added sets a price the wells were not searched at), and only
        // moving them with the drifts shows whether the assignment pays.
        if !well_searches.retry_fitting || totals(tables, picks).1 < best_dv {
            return Ok(Some(price));
        }
    }
    if well_searches.left == 0
        || !has_well_leg(tables, picks)
        || dv_floor_mps(tables, picks) >= best_dv
    {
        return Ok(None);
    }
    well_searches.left = well_searches.left.saturating_sub(1);
    wells_allocate(
        tables,
        picks,
        budget_s,
        s,
        iterations,
        (hint, best_dv),
        meter,
    )
}

/// One trial of the exchange search (a leg's or a pair of legs' change, already written into
/// `trial`) re-allocated by [`reallocate`] from `price`: its new price and total Δv when it fits
/// `budget_s` and lowers the total below `best_dv`, `None` otherwise; [`Cut`] as
/// [`reallocate`]. Shared by the one-leg rounds ([`super::exchange`]) and the pair stage
/// ([`super::exchange_pairs`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn trial_improves(
    tables: &[LegTable],
    trial: &mut [Pick],
    budget_s: f64,
    s: &Settings,
    iterations: &mut u32,
    price: f64,
    (best_dv, well_searches): (f64, &mut WellSearches),
    meter: &mut Meter,
) -> Result<Option<(f64, f64)>, Cut> {
    let Some(p) = reallocate(
        tables,
        trial,
        budget_s,
        s,
        iterations,
        Some(price),
        (best_dv, well_searches),
        meter,
    )?
    else {
        return Ok(None);
    };
    let (time_s, dv) = totals(tables, trial);
    Ok((time_s <= budget_s && dv < best_dv - 1e-12).then_some((p, dv)))
}

/// The searches moving the wells ([`wells_allocate`]) a caller of [`reallocate`] allows.
pub(super) struct WellSearches {
    /// How many may still start.
    pub left: u8,
    /// Whether an assignment that fits by its drifts alone but does not beat the best is
    /// searched again with its wells moved (the exchange search, for a leg turned to a
    /// drift).
    pub retry_fitting: bool,
}
