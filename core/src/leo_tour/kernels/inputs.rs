//! The inputs of the LEO kernel cases ([`super`]): Table 1's clients, the paper's arc, the
//! search-model cases' orbits and the sequencing cases' tours.

use super::super::elements::{state_of, Classical};
use super::super::j2::State;
use super::super::sequence::{Intervals, SequenceProblem, SequenceSettings, MAX_CLIENTS};
use super::super::tour_order::ESTIMATE_SETTINGS;
use super::super::types::{ArcProblem, Settings};

/// One degree, rad.
const DEG: f64 = core::f64::consts::PI / 180.0;

/// The orbit of a search-model case.
#[derive(Clone, Copy, Debug)]
pub(super) enum Orbit {
    /// Table 1's client S1 (a = 6778.14 km, circular, i = 97.03 deg).
    Paper,
    /// a = 30000 km, e = 0.75 (perigee altitude 1122 km), near apogee: Kepler's equation at
    /// its slowest.
    HighEcc,
}

/// The tour of a sequencing case.
#[derive(Clone, Copy, Debug)]
pub(super) enum Tour {
    /// Example I's five clients and printed intervals, the estimates' and the sequencing's
    /// defaults (the on-board fixture `leo-tour-example1-sequence.toml`).
    ExampleOne,
    /// Eight clients, every estimate refused at its checks (one impulse per arc): the
    /// enumeration's nodes and arcs alone, each arc charged a solve's fixed part.
    EightRefused,
    /// Eight clients, estimates of one grid epoch and ten evaluations, the default budget:
    /// hundreds of arcs, the memos filled.
    EightCoarse,
}

/// The request of a sequencing case: the tour and both settings.
pub(super) fn sequence_case(tour: Tour) -> Option<(SequenceProblem, SequenceSettings, Settings)> {
    let mut clients = heapless::Vec::new();
    let (count, intervals) = match tour {
        Tour::ExampleOne => {
            for (a, i, raan, u) in [
                (6778.14, 97.0344, 49.0, 25.0),
                (6878.14, 97.4063, 46.0, 13.0),
                (6978.14, 97.7924, 50.5836, 5.0),
                (7078.14, 98.1929, 51.0, 50.0),
                (7178.14, 98.6078, 48.3129, 349.9999),
            ] {
                clients.push(client(a, i, raan, u)?).ok()?;
            }
            let dt_max = 166_608.838_7;
            let mut list = [dt_max; MAX_CLIENTS - 1];
            *list.first_mut()? = 83_304.419_4;
            (5, list)
        }
        Tour::EightRefused | Tour::EightCoarse => {
            for (k, spread) in (0..MAX_CLIENTS).zip([0.0, 3.0, 1.0, 4.0, 2.0, 0.0, 3.0, 1.0]) {
                let x = k as f64;
                let raan = 46.0 + 1.3 * spread;
                clients
                    .push(client(
                        6778.14 + 60.0 * x,
                        97.03 + 0.24 * x,
                        raan,
                        45.0 * x,
                    )?)
                    .ok()?;
            }
            (MAX_CLIENTS, [86_400.0; MAX_CLIENTS - 1])
        }
    };
    let problem = SequenceProblem {
        clients,
        impulses: if matches!(tour, Tour::EightRefused) {
            1
        } else {
            3
        },
        first: None,
        intervals: Intervals::ByPosition(intervals),
    };
    let estimates = match tour {
        Tour::EightCoarse => Settings {
            grid_points: 1,
            search_max_evals: 10,
            ..ESTIMATE_SETTINGS
        },
        _ => ESTIMATE_SETTINGS,
    };
    (problem.clients.len() == count).then_some((problem, SequenceSettings::DEFAULT, estimates))
}

/// Table 1's client (circular) at `u_deg` of argument of latitude.
fn client(a_km: f64, i_deg: f64, raan_deg: f64, u_deg: f64) -> Option<State> {
    state_of(
        crate::astro::EARTH_MU_KM3_S2,
        &Classical {
            a_km,
            e: 0.0,
            i_rad: i_deg * DEG,
            raan_rad: raan_deg * DEG,
            argp_rad: 0.0,
            nu_rad: u_deg * DEG,
        },
    )
}

/// The paper's single arc S1 -> S2 (Table 1, three impulses, 83304.4194 s; the fixture
/// `leo-tour-example1-single-arc.toml`).
pub fn paper_arc() -> Option<ArcProblem> {
    Some(ArcProblem {
        from: client(6778.14, 97.0344, 49.0, 25.0)?,
        to: client(6878.14, 97.4063, 46.0, 13.0)?,
        duration_s: 83_304.419_4,
        impulses: 3,
    })
}

pub(super) fn orbit_state(orbit: Orbit) -> Option<State> {
    match orbit {
        Orbit::Paper => client(6778.14, 97.0344, 49.0, 25.0),
        Orbit::HighEcc => state_of(
            crate::astro::EARTH_MU_KM3_S2,
            &Classical {
                a_km: 30_000.0,
                e: 0.75,
                i_rad: 63.4 * DEG,
                raan_rad: 10.0 * DEG,
                argp_rad: 30.0 * DEG,
                nu_rad: 170.0 * DEG,
            },
        ),
    }
}
