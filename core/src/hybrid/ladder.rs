//! The homotopy from minimum energy to minimum fuel (SPEC-hybrid.md §2 item 8): the smoothed
//! law's ε lowered step by step, each shooting started from the previous step's costates. A
//! step that does not converge is retried with half the reduction; the ladder stops at the
//! target ε, at its step bound, or where a step fails at its smallest reduction, and says
//! which ε it reached (a status, never a silent best effort).

use super::dynamics::Throttle;
use super::integrate::Counts;
use super::shooting::{shoot, Settings, Solution, Status, Transfer};
use super::Model;

/// The ε below which the ladder jumps to its target (measured on Table 3's first group: the
/// smoothed law's steps fail below ε ≈ 0.024, where its ramp is steeper than the steps).
pub const JUMP_BELOW: f64 = 0.03;

/// How far the ladder went.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ladder {
    /// Whether it reached the target ε.
    pub reached: bool,
    /// The smallest ε at which the shooting converged.
    pub epsilon: f64,
    /// The converged shooting at that ε.
    pub solution: Solution,
    /// Shootings run (converged or not).
    pub steps: u32,
    /// All the shootings' integrations.
    pub counts: Counts,
}

/// Lower ε from the transfer's law (converged at `costates`) to `target_epsilon`, halving it
/// at each step, in at most `max_steps` shootings. `None` when the transfer's own law does not
/// converge from `costates` (no rung to stand on).
pub fn descend(
    model: &Model,
    transfer: &Transfer,
    costates: &[f64; 7],
    target_epsilon: f64,
    max_steps: u32,
    settings: &Settings,
) -> Option<Ladder> {
    let first = shoot(model, transfer, costates, settings);
    let Throttle::Smoothed { epsilon: start } = transfer.law else {
        return None;
    };
    if first.status != Status::Converged {
        return None;
    }
    let mut counts = first.counts;
    let mut at = Ladder {
        reached: start <= target_epsilon,
        epsilon: start,
        solution: first,
        steps: 1,
        counts,
    };
    // The next ε as a fraction of the current one: 1/2, raised toward 1 after a failure.
    let mut ratio = 0.5;
    while !at.reached && at.steps < max_steps && ratio < 0.99 {
        // Below JUMP_BELOW the ramp is too steep for the integrator's steps: go to the target
        // at once (at ε = 0 the bang-bang law, its switches located).
        let next = if at.epsilon * ratio < JUMP_BELOW {
            target_epsilon
        } else {
            (at.epsilon * ratio).max(target_epsilon)
        };
        let rung = Transfer {
            law: Throttle::Smoothed { epsilon: next },
            ..*transfer
        };
        let s = shoot(model, &rung, &at.solution.costates, settings);
        at.steps = at.steps.saturating_add(1);
        counts.accepted = counts.accepted.saturating_add(s.counts.accepted);
        counts.rejected = counts.rejected.saturating_add(s.counts.rejected);
        counts.evaluations = counts.evaluations.saturating_add(s.counts.evaluations);
        at.counts = counts;
        if s.status == Status::Converged {
            at.epsilon = next;
            at.solution = s;
            at.reached = next <= target_epsilon;
            ratio = 0.5;
        } else {
            ratio = libm::sqrt(ratio);
        }
    }
    Some(at)
}

/// How far a continuation in the time of flight went.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Walk {
    /// Whether it reached the target time of flight.
    pub reached: bool,
    /// The time of flight of the last converged shooting, TU.
    pub duration_tu: f64,
    /// That shooting.
    pub solution: Solution,
    /// Shootings run (converged or not).
    pub steps: u32,
}

/// Walk the transfer's time of flight to `target_tu` by steps of at most `step_tu`, each
/// shooting started from the previous one's costates (converged at `costates` for the
/// transfer's own time); a failed step is retried at half the size, down to a thousandth of
/// `step_tu`; at most `max_steps` shootings. `None` when the transfer itself does not
/// converge from `costates`.
pub fn walk_duration(
    model: &Model,
    transfer: &Transfer,
    costates: &[f64; 7],
    target_tu: f64,
    step_tu: f64,
    max_steps: u32,
    settings: &Settings,
) -> Option<Walk> {
    let first = shoot(model, transfer, costates, settings);
    if first.status != Status::Converged {
        return None;
    }
    let mut at = Walk {
        reached: (transfer.duration_tu - target_tu).abs() <= f64::EPSILON * target_tu.abs(),
        duration_tu: transfer.duration_tu,
        solution: first,
        steps: 1,
    };
    let mut size = step_tu.abs();
    while !at.reached && at.steps < max_steps && size >= step_tu.abs() * 1e-3 {
        let gap = target_tu - at.duration_tu;
        let last = gap.abs() <= size;
        let next = if last {
            target_tu
        } else {
            at.duration_tu + size * gap.signum()
        };
        let leg = Transfer {
            duration_tu: next,
            ..*transfer
        };
        let s = shoot(model, &leg, &at.solution.costates, settings);
        at.steps = at.steps.saturating_add(1);
        if s.status == Status::Converged {
            at.duration_tu = next;
            at.solution = s;
            at.reached = last;
        } else {
            size *= 0.5;
        }
    }
    Some(at)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hybrid::departure::Departure;
    use crate::hybrid::flow::propagate;
    use crate::hybrid::integrate::Counts;
    use crate::hybrid::min_time::{self, Endpoints, Unknowns};
    use crate::hybrid::units::{days, time_tu};

    fn table_3_transfer(days: f64) -> Transfer {
        let x0 = Departure::paper().state(1.4, -2.0).state;
        Transfer {
            departure_r_lu: [x0[0], x0[1], x0[2]],
            departure_v_vu: [x0[3], x0[4], x0[5]],
            departure_m_mu: x0[6],
            arrival_r_lu: [0.823_385_182_067, 0.0, -0.022_277_556_273],
            arrival_v_vu: [0.0, 0.134_184_170_262, 0.0],
            duration_tu: time_tu(days),
            law: Throttle::Smoothed { epsilon: 1.0 },
        }
    }

    /// Table 3's first group (κ = 1.40, θ = −2, κ and θ fixed), minimum fuel: minimum energy
    /// at 4.3800 d from costates near the ones a seeded multistart found, the ladder to ε = 0
    /// (bang-bang, switches located), then the shorter flights by continuation in t_f from the
    /// minimum-energy costates. Final masses within 1e-4 of the printed 0.3365 and 0.3341; at
    /// 3.7061 d, where the ladder stalls at ε ≈ 0.13, by walking t_f down at ε = 0 instead
    /// (0.3306). Then Table 2's minimum time at κ = 1.40 from the minimum-fuel direction.
    #[test]
    fn the_ladder_reaches_table_3s_fixed_kappa_rows_and_table_2s_minimum_time() {
        let model = Model::paper();
        let settings = Settings {
            max_iterations: 40,
            max_halvings: 20,
            ..Settings::default()
        };
        let mut fuel_costates = None;
        // The minimum-energy costates at 4.38 d, to four digits (the shooting refines them).
        let mut energy = [
            1.635, 7.972, -0.069_96, -0.020_72, 0.016_16, 9.53e-6, 0.066_14,
        ];
        for (days, printed) in [(4.3800, 0.3365), (4.0431, 0.3341)] {
            let transfer = table_3_transfer(days);
            let ladder = descend(&model, &transfer, &energy, 0.0, 12, &settings).unwrap();
            assert!(
                ladder.reached && ladder.epsilon == 0.0,
                "{days} d: {ladder:?}"
            );
            assert!(ladder.solution.residual <= 1e-10, "{days} d: {ladder:?}");
            let fuel = Transfer {
                law: Throttle::Smoothed { epsilon: 0.0 },
                ..transfer
            };
            let y0 = fuel.initial(&ladder.solution.costates);
            let mut counts = Counts::default();
            let tol = &settings.integration;
            let end = propagate(&model, fuel.law, &y0, fuel.duration_tu, tol, &mut counts).unwrap();
            assert!(
                (end.m_mu - printed).abs() < 1e-4,
                "{days} d: m_f {} against {printed}",
                end.m_mu
            );
            // H is constant along the minimum-fuel solution (issue 30: to 1e-10).
            let h0 = model.hamiltonian(fuel.law, &y0);
            for k in 1..=10 {
                let t = fuel.duration_tu * f64::from(k) / 10.0;
                let y = propagate(&model, fuel.law, &y0, t, tol, &mut counts).unwrap();
                assert!(
                    (model.hamiltonian(fuel.law, &y) - h0).abs() < 1e-10,
                    "{days} d: H"
                );
            }
            // The next (shorter) flight starts from this one's minimum-energy costates.
            let first = shoot(&model, &transfer, &energy, &settings);
            assert_eq!(first.status, Status::Converged);
            energy = first.costates;
            fuel_costates = Some(ladder.solution.costates);
        }
        // The third row, 3.7061 d, where the ladder stalls (ε ≈ 0.15): walked at ε = 0 from
        // the 4.0431 d minimum-fuel costates by steps of 0.05 d.
        let walk = walk_duration(
            &model,
            &Transfer {
                law: Throttle::Smoothed { epsilon: 0.0 },
                ..table_3_transfer(4.0431)
            },
            &fuel_costates.unwrap(),
            time_tu(3.7061),
            time_tu(0.05),
            20,
            &settings,
        )
        .unwrap();
        assert!(walk.reached && walk.steps <= 10, "{walk:?}");
        let fuel = Transfer {
            law: Throttle::Smoothed { epsilon: 0.0 },
            ..table_3_transfer(3.7061)
        };
        let mut counts = Counts::default();
        let y0 = fuel.initial(&walk.solution.costates);
        let tol = &settings.integration;
        let end = propagate(&model, fuel.law, &y0, fuel.duration_tu, tol, &mut counts).unwrap();
        assert!(
            (end.m_mu - 0.3306).abs() < 1e-4,
            "3.7061 d: m_f {}",
            end.m_mu
        );
        // Table 2, κ = 1.40 (θ = −2): minimum time from the direction of the 4.0431 d
        // minimum-fuel costates (λ0 = 0.1, any of 1e-3 to 3 converges alike), t_f from 4.0431 d.
        let lam = fuel_costates.unwrap();
        let raw = [0.1, lam[0], lam[1], lam[2], lam[3], lam[4], lam[5], lam[6]];
        let norm = libm::sqrt(raw.iter().map(|x| x * x).sum::<f64>());
        let x0 = Departure::paper().state(1.4, -2.0).state;
        let ends = Endpoints {
            departure_r_lu: [x0[0], x0[1], x0[2]],
            departure_v_vu: [x0[3], x0[4], x0[5]],
            departure_m_mu: x0[6],
            arrival_r_lu: [0.823_385_182_067, 0.0, -0.022_277_556_273],
            arrival_v_vu: [0.0, 0.134_184_170_262, 0.0],
        };
        let guess = Unknowns {
            multipliers: raw.map(|x| x / norm),
            duration_tu: time_tu(4.0431),
        };
        let fastest = min_time::shoot(&model, &ends, &guess, &settings);
        assert_eq!(fastest.status, Status::Converged, "{fastest:?}");
        let t_min_days = days(fastest.unknowns.duration_tu);
        assert!((t_min_days - 3.3692).abs() < 1e-3, "t_min {t_min_days} d");
        let m_f = x0[6] - model.thrust_fu / model.exhaust_vu * fastest.unknowns.duration_tu;
        assert!((m_f - 0.3200).abs() < 1e-4, "m_f {m_f}");
    }
}
