//! Planner codes and the names of settings: `reconfig_setting_name(planner, code)` turns the
//! `error.index` of a `RECONFIG_ERR_SETTING_OUT_OF_RANGE` or `RECONFIG_ERR_LIMIT_EXCEEDED`
//! refusal into the setting's name (its field in the C struct, its fixture key, its limits-file
//! key), read from the core's settings tables at compile time: static, NUL-terminated, no
//! allocation.

use core::ffi::c_char;
use reconfig_core::contract::PlannerKind;
use reconfig_core::limits::ProblemLimit;
use reconfig_core::{geo_tour, hybrid, impulsive, leo_tour, pseudospectral};

/// Planner A (`reconfig_pseudospectral_*`).
pub const RECONFIG_PLANNER_PSEUDOSPECTRAL: i32 = 0;
/// Planner B (`reconfig_impulsive_*`, both input forms).
pub const RECONFIG_PLANNER_IMPULSIVE: i32 = 1;
/// The GEO servicing tour (`reconfig_geo_tour_*`).
pub const RECONFIG_PLANNER_GEO_TOUR: i32 = 2;
/// One arc of the LEO tour (`reconfig_leo_arc_*`).
pub const RECONFIG_PLANNER_LEO_ARC: i32 = 3;
/// The hybrid chemical + electric transfer (`reconfig_hybrid_*`). Code 4, the LEO tour's
/// sequencing, has no C interface: `reconfig_setting_name` answers NULL for it.
pub const RECONFIG_PLANNER_HYBRID: i32 = 5;

// Literals so that the header can spell them; the wire's planner codes decide.
const _: () = assert!(RECONFIG_PLANNER_PSEUDOSPECTRAL == PlannerKind::Pseudospectral as i32);
const _: () = assert!(RECONFIG_PLANNER_IMPULSIVE == PlannerKind::Impulsive as i32);
const _: () = assert!(RECONFIG_PLANNER_GEO_TOUR == PlannerKind::GeoTour as i32);
const _: () = assert!(RECONFIG_PLANNER_LEO_ARC == PlannerKind::LeoArc as i32);
const _: () = assert!(RECONFIG_PLANNER_HYBRID == PlannerKind::Hybrid as i32);

/// Bytes of one name slot, the NUL included.
const NAME_BYTES: usize = 40;
type Name = [u8; NAME_BYTES];

/// `name` followed by NULs. Evaluated at compile time only (the tables below are statics): a
/// name too long for its slot is a compile error, not a run-time path.
#[allow(clippy::indexing_slicing, clippy::arithmetic_side_effects)]
const fn nul_terminated(name: &str) -> Name {
    let bytes = name.as_bytes();
    assert!(
        bytes.len() < NAME_BYTES,
        "a setting name is longer than its slot"
    );
    let mut out = [0u8; NAME_BYTES];
    let mut i = 0;
    while i < bytes.len() {
        out[i] = bytes[i];
        i += 1;
    }
    out
}

/// One planner's names, indexed by setting code (a slot of the table's size for each code up
/// to the largest; a code no setting has stays empty).
macro_rules! names_by_code {
    ($Id:ty) => {{
        const LEN: usize = {
            let mut len = 0;
            let mut i = 0;
            while i < <$Id>::ALL.len() {
                let next = <$Id>::ALL[i] as usize + 1;
                if next > len {
                    len = next;
                }
                i += 1;
            }
            len
        };
        let mut table = [[0u8; NAME_BYTES]; LEN];
        let mut i = 0;
        while i < <$Id>::ALL.len() {
            let id = <$Id>::ALL[i];
            table[id as usize] = nul_terminated(id.name());
            i += 1;
        }
        table
    }};
}

/// Every problem quantity the limits bound, in code order (`ProblemLimit` has no list of its
/// own; [`every_problem_limit_is_listed`] fails to compile when a variant is added).
const PROBLEM_LIMITS: [ProblemLimit; 14] = [
    ProblemLimit::Spacecraft,
    ProblemLimit::Degree,
    ProblemLimit::Impulses,
    ProblemLimit::Search,
    ProblemLimit::ChiefEccentricity,
    ProblemLimit::ChiefPerigeeAltitudeKm,
    ProblemLimit::DeputyInitialEccentricity,
    ProblemLimit::DeputyInitialPerigeeAltitudeKm,
    ProblemLimit::DeputyTargetEccentricity,
    ProblemLimit::DeputyTargetPerigeeAltitudeKm,
    ProblemLimit::RoeChiefSinInclination,
    ProblemLimit::Targets,
    ProblemLimit::ArcImpulses,
    ProblemLimit::Clients,
];

/// Exhaustive: a new `ProblemLimit` variant fails to compile here until it is listed above.
#[allow(dead_code)]
const fn every_problem_limit_is_listed(p: ProblemLimit) {
    match p {
        ProblemLimit::Spacecraft
        | ProblemLimit::Degree
        | ProblemLimit::Impulses
        | ProblemLimit::Search
        | ProblemLimit::ChiefEccentricity
        | ProblemLimit::ChiefPerigeeAltitudeKm
        | ProblemLimit::DeputyInitialEccentricity
        | ProblemLimit::DeputyInitialPerigeeAltitudeKm
        | ProblemLimit::DeputyTargetEccentricity
        | ProblemLimit::DeputyTargetPerigeeAltitudeKm
        | ProblemLimit::RoeChiefSinInclination
        | ProblemLimit::Targets
        | ProblemLimit::ArcImpulses
        | ProblemLimit::Clients => {}
    }
}

#[allow(clippy::indexing_slicing, clippy::arithmetic_side_effects)]
const fn problem_names() -> [Name; PROBLEM_LIMITS.len()] {
    let mut table = [[0u8; NAME_BYTES]; PROBLEM_LIMITS.len()];
    let mut i = 0;
    while i < PROBLEM_LIMITS.len() {
        let p = PROBLEM_LIMITS[i];
        assert!(p as usize == i, "PROBLEM_LIMITS is in code order");
        table[i] = nul_terminated(p.name());
        i += 1;
    }
    table
}

// Built at compile time (the indexing and arithmetic in these initialisers cannot run later).
#[allow(clippy::indexing_slicing, clippy::arithmetic_side_effects)]
static A_NAMES: [Name; pseudospectral::SettingId::ALL.len()] =
    names_by_code!(pseudospectral::SettingId);
#[allow(clippy::indexing_slicing, clippy::arithmetic_side_effects)]
static B_NAMES: [Name; impulsive::SettingId::ALL.len()] = names_by_code!(impulsive::SettingId);
#[allow(clippy::indexing_slicing, clippy::arithmetic_side_effects)]
static GEO_NAMES: [Name; geo_tour::SettingId::ALL.len()] = names_by_code!(geo_tour::SettingId);
#[allow(clippy::indexing_slicing, clippy::arithmetic_side_effects)]
static LEO_ARC_NAMES: [Name; leo_tour::SettingId::ALL.len()] = names_by_code!(leo_tour::SettingId);
#[allow(clippy::indexing_slicing, clippy::arithmetic_side_effects)]
static HYBRID_NAMES: [Name; hybrid::SettingId::ALL.len()] = names_by_code!(hybrid::SettingId);
static PROBLEM_NAMES: [Name; PROBLEM_LIMITS.len()] = problem_names();

/// The NUL-terminated name of setting `code` of `planner`, if any.
fn name_slot(planner: i32, code: i32) -> Option<&'static Name> {
    let code = u8::try_from(code).ok()?;
    let slot = if code >= ProblemLimit::CODE_BASE {
        let p = PROBLEM_LIMITS
            .get(usize::from(code.wrapping_sub(ProblemLimit::CODE_BASE)))
            .copied()?;
        if p.planner() as i32 != planner {
            return None;
        }
        PROBLEM_NAMES.get(p as usize)?
    } else {
        let table: &[Name] = match planner {
            RECONFIG_PLANNER_PSEUDOSPECTRAL => &A_NAMES,
            RECONFIG_PLANNER_IMPULSIVE => &B_NAMES,
            RECONFIG_PLANNER_GEO_TOUR => &GEO_NAMES,
            RECONFIG_PLANNER_LEO_ARC => &LEO_ARC_NAMES,
            RECONFIG_PLANNER_HYBRID => &HYBRID_NAMES,
            _ => return None,
        };
        table.get(usize::from(code))?
    };
    // An empty slot is a code no setting has.
    (slot.first().copied().unwrap_or(0) != 0).then_some(slot)
}

/// The name of the setting or problem quantity a refusal names: `planner` a
/// `RECONFIG_PLANNER_*` code, `code` the refusal's `error.index` (a setting's code in its
/// planner's settings table, or 128 plus a problem quantity's code). Returns a static
/// NUL-terminated string (never to be freed; the same pointer every call), or NULL for a code
/// the planner has no setting for.
#[no_mangle]
pub extern "C" fn reconfig_setting_name(planner: i32, code: i32) -> *const c_char {
    match name_slot(planner, code) {
        Some(name) => name.as_ptr().cast::<c_char>(),
        None => core::ptr::null(),
    }
}
