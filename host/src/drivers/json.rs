//! The JSON object `reconfig solve --json` prints for an answered fixture of one request, as a
//! value, for a front end that hands it on rather than prints it (the Python package): the
//! planner's own report object, or the shared one of a refusal, a rejection or an answer
//! without a report of its own. The same functions build what `reconfig solve --json` prints.

use super::answer::{other_json, Answered};
use super::{geo_tour, hybrid, impulsive, pseudospectral};
use crate::fixture::Fixture;
use anyhow::Result;
use reconfig_core::wire::OutcomeRef;
use serde_json::Value;

/// The JSON object of `fixture`'s one request answered as `answered`.
///
/// # Errors
/// An outcome that no request of a fixture can have, or an end state that cannot be written
/// (as `reconfig solve`).
pub fn of(fixture: &Fixture, answered: &Answered) -> Result<Value> {
    match (fixture, &answered.outcome) {
        (Fixture::Pseudospectral(f), OutcomeRef::Pseudospectral(s)) => {
            Ok(pseudospectral::to_json(&f.name, s, answered.time_s))
        }
        (
            Fixture::Impulsive(f),
            OutcomeRef::Impulsive(s) | OutcomeRef::ImpulsiveForm { solution: s, .. },
        ) => impulsive::to_json(f, s, answered.time_s),
        (Fixture::GeoTour(f), OutcomeRef::GeoTour(s)) => Ok(geo_tour::to_json(
            &f.name,
            f.problem.mission_time_s,
            s,
            answered.time_s,
        )),
        (Fixture::Hybrid(f), OutcomeRef::Hybrid(s)) => {
            Ok(hybrid::answered_json(f, s, answered.time_s))
        }
        _ => other_json(fixture.name(), answered),
    }
}
