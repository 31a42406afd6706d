//! The shooting a request's objective and free parameters call for (fixed time with κ and θ
//! fixed or free, or minimum time), from the request's start, as one [`Shot`].

use super::departure::Departure;
use super::dynamics::{Model, Throttle};
use super::free::{self, Free, ImpulseTransfer, Point};
use super::integrate::Counts;
use super::min_time::{self, Endpoints, Unknowns};
use super::problem::{Objective, Problem};
use super::shooting::{self, Status, Transfer};
use super::units;

/// The shooting's end, whatever the objective.
pub(super) struct Shot {
    /// How the shooting ended.
    pub status: Status,
    /// The converged unknowns, or the best iterate (κ and θ as given where fixed).
    pub point: Point,
    /// λ0 (1 for the fixed-time objectives).
    pub cost_multiplier: f64,
    /// The time of flight, TU.
    pub duration_tu: f64,
    /// Largest component of the residual (infinite where it could not be flown).
    pub residual: f64,
    /// Newton iterations.
    pub iterations: u32,
    /// The integrations' work.
    pub counts: Counts,
}

/// The model of the request's electric engine in the paper's CR3BP.
pub(super) fn model_of(problem: &Problem) -> Model {
    Model {
        mass_ratio: units::MASS_RATIO,
        thrust_fu: units::force_fu(problem.thrust_n),
        exhaust_vu: units::exhaust_speed_vu(problem.specific_impulse_s),
    }
}

/// The request's parking orbit and chemical engine.
pub(super) fn departure_of(problem: &Problem) -> Departure {
    Departure {
        mass_ratio: units::MASS_RATIO,
        parking_radius_lu: units::distance_lu(problem.parking_radius_km),
        chemical_exhaust_vu: units::exhaust_speed_vu(problem.chemical_specific_impulse_s),
    }
}

/// The throttle law of a fixed-time objective.
pub(super) fn law(objective: Objective) -> Throttle {
    match objective {
        Objective::MinFuel => Throttle::Smoothed { epsilon: 0.0 },
        Objective::MinEnergy => Throttle::Smoothed { epsilon: 1.0 },
        Objective::MinTime => Throttle::Full,
    }
}

/// The state after the impulse with the navigation update added.
pub(super) fn departure_state(departure: &Departure, problem: &Problem) -> [f64; 7] {
    let mut x = departure.state(problem.kappa, problem.theta_rad).state;
    for (xi, di) in x.iter_mut().zip(problem.departure_offset) {
        *xi += di;
    }
    x
}

/// Run the shooting the objective and the free parameters call for.
pub(super) fn shoot(
    model: &Model,
    departure: &Departure,
    problem: &Problem,
    settings: &shooting::Settings,
) -> Shot {
    let duration_tu = units::time_tu(problem.duration_days);
    let start = Point {
        costates: problem.costates,
        kappa: problem.kappa,
        theta_rad: problem.theta_rad,
    };
    let x = departure_state(departure, problem);
    let (r, v) = ([x[0], x[1], x[2]], [x[3], x[4], x[5]]);
    match problem.objective {
        Objective::MinTime => {
            let ends = Endpoints {
                departure_r_lu: r,
                departure_v_vu: v,
                departure_m_mu: x[6],
                arrival_r_lu: problem.arrival_r_lu,
                arrival_v_vu: problem.arrival_v_vu,
            };
            let c = problem.costates;
            let guess = Unknowns {
                multipliers: [
                    problem.cost_multiplier,
                    c[0],
                    c[1],
                    c[2],
                    c[3],
                    c[4],
                    c[5],
                    c[6],
                ],
                duration_tu,
            };
            let s = min_time::shoot(model, &ends, &guess, settings);
            let p = s.unknowns.multipliers;
            Shot {
                status: s.status,
                point: Point {
                    costates: [p[1], p[2], p[3], p[4], p[5], p[6], p[7]],
                    ..start
                },
                cost_multiplier: p[0],
                duration_tu: s.unknowns.duration_tu,
                residual: s.residual,
                iterations: s.iterations,
                counts: s.counts,
            }
        }
        Objective::MinFuel | Objective::MinEnergy if problem.free_kappa || problem.free_theta => {
            let transfer = ImpulseTransfer {
                departure: *departure,
                arrival_r_lu: problem.arrival_r_lu,
                arrival_v_vu: problem.arrival_v_vu,
                duration_tu,
                law: law(problem.objective),
                free: Free {
                    kappa: problem.free_kappa,
                    theta: problem.free_theta,
                },
                offset: problem.departure_offset,
            };
            let s = free::shoot(model, &transfer, &start, settings);
            Shot {
                status: s.status,
                point: s.point,
                cost_multiplier: 1.0,
                duration_tu,
                residual: s.residual,
                iterations: s.iterations,
                counts: s.counts,
            }
        }
        Objective::MinFuel | Objective::MinEnergy => {
            let transfer = Transfer {
                departure_r_lu: r,
                departure_v_vu: v,
                departure_m_mu: x[6],
                arrival_r_lu: problem.arrival_r_lu,
                arrival_v_vu: problem.arrival_v_vu,
                duration_tu,
                law: law(problem.objective),
            };
            let s = shooting::shoot(model, &transfer, &problem.costates, settings);
            Shot {
                status: s.status,
                point: Point {
                    costates: s.costates,
                    ..start
                },
                cost_multiplier: 1.0,
                duration_tu,
                residual: s.residual,
                iterations: s.iterations,
                counts: s.counts,
            }
        }
    }
}
