//! The flow of the canonical system and its state-transition matrix: the 14 unknowns alone, or
//! with the 196 variational equations `Φ' = A Φ`, `Φ(0) = I` (SPEC-hybrid.md eq. 19), on the
//! DOP853 integrator ([`super::integrate`]). The smoothed law with ε = 0 is bang-bang: it is
//! flown arc by arc, the throttle fixed on each, every switch (`S = 0`) located as the arc's
//! event, and the state-transition matrix carried across it by the jump of eq. 22,
//! `Ψ = I + (f⁺ − f⁻) (dS/dy)/Ṡ`.

use super::dynamics::{Augmented, Model, Throttle};
use super::integrate::{integrate, integrate_arc, Counts, Stop, Tolerance};
use super::jacobian::{jacobian, Jacobian};

/// The state and its state-transition matrix, as the integrator carries them: the 14 unknowns,
/// then Φ column by column.
type WithStm = [f64; 210];

/// Switches of the bang-bang law one propagation may cross.
pub const MAX_SWITCHES: u32 = 256;

/// Whether `law` is the bang-bang law (the smoothed law at ε = 0).
pub(super) fn bang_bang(law: Throttle) -> bool {
    matches!(law, Throttle::Smoothed { epsilon } if epsilon <= 0.0)
}

/// The throttle on the arc that starts at `y` (thrust where `S < 0`), and the sign that keeps
/// `polarity × S` non-negative along it.
fn arc_law(model: &Model, y: &Augmented) -> (Throttle, f64) {
    if model.switching(y) < 0.0 {
        (Throttle::Full, -1.0)
    } else {
        (Throttle::Coast, 1.0)
    }
}

/// The bang-bang flow, arc by arc; with `phi`, the state-transition matrix carried along and
/// across the switches; `on_switch` sees each switch (its time from the start, signed as the
/// duration, and the state there). Returns the end and the number of switches.
fn bang(
    model: &Model,
    y0: &Augmented,
    duration_tu: f64,
    tol: &Tolerance,
    counts: &mut Counts,
    mut phi: Option<&mut Jacobian>,
    on_switch: &mut dyn FnMut(f64, &Augmented),
) -> Result<(Augmented, u32), Stop> {
    let mut y = *y0;
    let mut left = duration_tu;
    let mut switches = 0_u32;
    loop {
        let (law, polarity) = arc_law(model, &y);
        let (end, time, event) = match phi.as_deref_mut() {
            None => {
                let f = |z: &[f64; 14]| model.derivative(law, &Augmented::from_array(z)).to_array();
                let g = |z: &[f64; 14]| polarity * model.switching(&Augmented::from_array(z));
                let arc = integrate_arc(f, g, &y.to_array(), left, first_step(left), tol, counts)?;
                (Augmented::from_array(&arc.end), arc.time, arc.event)
            }
            Some(phi) => {
                let mut start = [0.0; 210];
                pack(&y.to_array(), phi, &mut start);
                let g = |z: &WithStm| {
                    let (state, _) = unpack(z);
                    polarity * model.switching(&Augmented::from_array(&state))
                };
                let arc = integrate_arc(
                    with_stm(model, law),
                    g,
                    &start,
                    left,
                    first_step(left),
                    tol,
                    counts,
                )?;
                let (state, carried) = unpack(&arc.end);
                *phi = carried;
                (Augmented::from_array(&state), arc.time, arc.event)
            }
        };
        y = end;
        left -= time;
        if !event {
            return Ok((y, switches));
        }
        switches = switches.saturating_add(1);
        on_switch(duration_tu - left, &y);
        if switches > MAX_SWITCHES {
            return Err(Stop::SwitchLimit {
                time: duration_tu - left,
            });
        }
        if let Some(phi) = phi.as_deref_mut() {
            // Ψ = I + (f⁺ − f⁻) (dS/dy)/Ṡ at the switch.
            let rate = model.switching_rate(&y);
            if rate != 0.0 {
                let next = if polarity < 0.0 {
                    Throttle::Coast
                } else {
                    Throttle::Full
                };
                let before = model.derivative(law, &y).to_array();
                let after = model.derivative(next, &y).to_array();
                let mut jump = [0.0; 14];
                for ((j, a), b) in jump.iter_mut().zip(after).zip(before) {
                    *j = (a - b) / rate;
                }
                let jump = nalgebra::SVector::<f64, 14>::from(jump);
                let grad = nalgebra::SVector::<f64, 14>::from(model.switching_gradient(&y));
                let mut psi = Jacobian::identity();
                psi.ger(1.0, &jump, &grad, 1.0);
                let carried = *phi;
                psi.mul_to(&carried, phi);
            }
        }
    }
}

/// The derivative of the state with its state-transition matrix under `law`.
fn with_stm(model: &Model, law: Throttle) -> impl Fn(&WithStm) -> WithStm + '_ {
    move |z: &WithStm| {
        let (y, phi) = unpack(z);
        let state = Augmented::from_array(&y);
        let mut a_phi = Jacobian::zeros();
        jacobian(model, law, &state).mul_to(&phi, &mut a_phi);
        let mut out = [0.0; 210];
        pack(&model.derivative(law, &state).to_array(), &a_phi, &mut out);
        out
    }
}

/// The flow from `y0` over `duration_tu` (either sign).
///
/// # Errors
/// The integrator's [`Stop`].
pub fn propagate(
    model: &Model,
    law: Throttle,
    y0: &Augmented,
    duration_tu: f64,
    tol: &Tolerance,
    counts: &mut Counts,
) -> Result<Augmented, Stop> {
    if bang_bang(law) {
        return bang(model, y0, duration_tu, tol, counts, None, &mut |_, _| {}).map(|(y, _)| y);
    }
    let f = |y: &[f64; 14]| model.derivative(law, &Augmented::from_array(y)).to_array();
    let end = integrate(
        f,
        &y0.to_array(),
        duration_tu,
        first_step(duration_tu),
        tol,
        counts,
    )?;
    Ok(Augmented::from_array(&end))
}

/// As [`propagate`], and `on_switch` sees every switch of the bang-bang law (its time from
/// `y0`, signed as the duration, and the state there; never called for another law).
///
/// # Errors
/// The integrator's [`Stop`].
pub fn propagate_observed(
    model: &Model,
    law: Throttle,
    y0: &Augmented,
    duration_tu: f64,
    tol: &Tolerance,
    counts: &mut Counts,
    on_switch: &mut dyn FnMut(f64, &Augmented),
) -> Result<Augmented, Stop> {
    if bang_bang(law) {
        return bang(model, y0, duration_tu, tol, counts, None, on_switch).map(|(y, _)| y);
    }
    propagate(model, law, y0, duration_tu, tol, counts)
}

/// The flow from `y0` over `duration_tu` and its state-transition matrix `dy(t)/dy0`.
///
/// # Errors
/// The integrator's [`Stop`].
pub fn propagate_with_stm(
    model: &Model,
    law: Throttle,
    y0: &Augmented,
    duration_tu: f64,
    tol: &Tolerance,
    counts: &mut Counts,
) -> Result<(Augmented, Jacobian), Stop> {
    if bang_bang(law) {
        let mut phi = Jacobian::identity();
        let (end, _) = bang(
            model,
            y0,
            duration_tu,
            tol,
            counts,
            Some(&mut phi),
            &mut |_, _| {},
        )?;
        return Ok((end, phi));
    }
    let mut start = [0.0; 210];
    pack(&y0.to_array(), &Jacobian::identity(), &mut start);
    let f = with_stm(model, law);
    let end = integrate(f, &start, duration_tu, first_step(duration_tu), tol, counts)?;
    let (y, phi) = unpack(&end);
    Ok((Augmented::from_array(&y), phi))
}

/// A first step for the step control: a thousandth of the arc (it adapts from there).
fn first_step(duration_tu: f64) -> f64 {
    (duration_tu.abs() * 1e-3).max(1e-9)
}

/// `[y; Φ by columns]`.
fn pack(y: &[f64; 14], phi: &Jacobian, out: &mut WithStm) {
    let (head, tail) = out.split_at_mut(14);
    head.copy_from_slice(y);
    for (o, x) in tail.iter_mut().zip(phi.iter()) {
        *o = *x;
    }
}

/// The inverse of [`pack`].
fn unpack(z: &WithStm) -> ([f64; 14], Jacobian) {
    let mut y = [0.0; 14];
    let (head, tail) = z.split_at(14);
    y.copy_from_slice(head);
    (y, Jacobian::from_iterator(tail.iter().copied()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hybrid::dynamics::tests::sample;

    const TIGHT: Tolerance = Tolerance {
        relative: 1e-13,
        absolute: 1e-15,
        max_steps: 200_000,
    };

    /// SPEC-hybrid.md's terminal point: a periodic southern L1 halo orbit of period 2.746337
    /// TU and Jacobi constant 3.170130, flown ballistically (no costates: the engine is off).
    #[test]
    fn the_papers_halo_point_is_periodic() {
        let model = Model::paper();
        let halo = Augmented {
            r_lu: [0.823_385_182_067, 0.0, -0.022_277_556_273],
            v_vu: [0.0, 0.134_184_170_262, 0.0],
            m_mu: 0.5,
            ..Augmented::default()
        };
        // C = 2Ω − v², Ω = (x² + y²)/2 + (1−μ)/r1 + μ/r2.
        let mu = model.mass_ratio;
        let [x, y, z] = halo.r_lu;
        let r1 = libm::sqrt((x + mu) * (x + mu) + y * y + z * z);
        let r2 = libm::sqrt((x + mu - 1.0) * (x + mu - 1.0) + y * y + z * z);
        let v2 = 0.134_184_170_262_f64 * 0.134_184_170_262;
        let jacobi = x * x + y * y + 2.0 * (1.0 - mu) / r1 + 2.0 * mu / r2 - v2;
        assert!(
            (jacobi - 3.170_130).abs() < 5e-7,
            "Jacobi constant {jacobi}"
        );
        let mut counts = Counts::default();
        let law = Throttle::Smoothed { epsilon: 0.0 };
        let back = propagate(&model, law, &halo, 2.746_337, &TIGHT, &mut counts).unwrap();
        let miss: f64 = back
            .to_array()
            .iter()
            .zip(halo.to_array())
            .map(|(a, b)| (a - b) * (a - b))
            .sum();
        // The period is printed to 7 digits: 1e-6 TU at 0.13 LU/TU.
        assert!(
            libm::sqrt(miss) < 1e-6,
            "returns within {}",
            libm::sqrt(miss)
        );
        assert_eq!(back.m_mu, 0.5, "no thrust, no mass spent");
    }

    /// Along a thrusting arc (throttle between its bounds and at them) the Hamiltonian is
    /// constant, to the integrator's tolerance.
    #[test]
    fn the_hamiltonian_is_constant_along_a_solution() {
        let model = Model::paper();
        let law = Throttle::Smoothed { epsilon: 0.5 };
        let y0 = sample(model.switching(&sample(0.0)) - 0.2);
        let h0 = model.hamiltonian(law, &y0);
        let mut counts = Counts::default();
        let mut drift: f64 = 0.0;
        let mut mass = y0.m_mu;
        for k in 1..=8 {
            let y = propagate(&model, law, &y0, 0.1 * f64::from(k), &TIGHT, &mut counts).unwrap();
            drift = drift.max((model.hamiltonian(law, &y) - h0).abs());
            assert!(y.m_mu < mass, "the engine burns");
            mass = y.m_mu;
        }
        // Issue 30's bar: 1e-10 (the throttle's ramp ends are kinks the steps cross).
        assert!(drift < 1e-10, "H drifts by {drift} (H = {h0})");
    }

    /// Every column of `phi` against central differences of the flow from `y0` over
    /// `duration`, extrapolated (Richardson: fourth order).
    fn assert_stm_is_the_flows_derivative(
        model: &Model,
        law: Throttle,
        y0: &Augmented,
        duration: f64,
        phi: &Jacobian,
    ) {
        let base = y0.to_array();
        for col in 0..14 {
            // Not smaller: the adaptive steps differ between the perturbed flows, a noise of
            // the tolerance (1e-13) over the step that grows as the step shrinks (measured:
            // up to 1e-6 of an entry at h = 1e-4; hence the 1e-5 below, while a wrong term
            // or a column out of place is wrong at O(1)).
            let h = 1e-4 * (1.0 + base[col].abs());
            let at = |dx: f64| {
                let mut z = base;
                z[col] += dx;
                let mut c = Counts::default();
                propagate(
                    model,
                    law,
                    &Augmented::from_array(&z),
                    duration,
                    &TIGHT,
                    &mut c,
                )
                .unwrap()
                .to_array()
            };
            // Central differences at h and h/2, extrapolated (Richardson): fourth order.
            let (plus, minus) = (at(h), at(-h));
            let (plus2, minus2) = (at(h / 2.0), at(-h / 2.0));
            for row in 0..14 {
                let coarse = (plus[row] - minus[row]) / (2.0 * h);
                let fine = (plus2[row] - minus2[row]) / h;
                let fd = (4.0 * fine - coarse) / 3.0;
                assert!(
                    (phi[(row, col)] - fd).abs() < 1e-5 * (1.0 + fd.abs()),
                    "Φ[{row}][{col}] = {} against {fd}",
                    phi[(row, col)]
                );
            }
        }
    }

    /// The bang-bang law (ε = 0): the arc coasts, switches the engine on where S crosses zero,
    /// and the state-transition matrix, carried across the switch by eq. 22's jump, is the
    /// flow's derivative; H is constant across the switch.
    #[test]
    fn the_bang_bang_flow_switches_and_its_matrix_jumps() {
        let model = Model::paper();
        let law = Throttle::Smoothed { epsilon: 0.0 };
        let y0 = sample(model.switching(&sample(0.0)) - 0.1);
        assert!(model.switching(&y0) > 0.0 && model.switching_rate(&y0) < 0.0);
        let duration = 0.6;
        let mut counts = Counts::default();
        let mut phi = Jacobian::identity();
        let (end, switches) = bang(
            &model,
            &y0,
            duration,
            &TIGHT,
            &mut counts,
            Some(&mut phi),
            &mut |_, _| {},
        )
        .unwrap();
        assert!(switches >= 1, "the engine switched on");
        let (alone, _) = bang(
            &model,
            &y0,
            duration,
            &TIGHT,
            &mut counts,
            None,
            &mut |_, _| {},
        )
        .unwrap();
        for (a, b) in end.to_array().iter().zip(alone.to_array()) {
            assert!((a - b).abs() < 1e-10 * (1.0 + b.abs()), "the same flow");
        }
        let h0 = model.hamiltonian(law, &y0);
        assert!(
            (model.hamiltonian(law, &end) - h0).abs() < 1e-10,
            "H across the switch"
        );
        assert_stm_is_the_flows_derivative(&model, law, &y0, duration, &phi);
    }

    /// The state-transition matrix is the flow's derivative: every column against central
    /// differences of the flow, over an arc on which the throttle crosses its bounds.
    #[test]
    fn the_state_transition_matrix_is_the_flows_derivative() {
        let model = Model::paper();
        let law = Throttle::Smoothed { epsilon: 0.3 };
        let y0 = sample(model.switching(&sample(0.0)) - 0.25);
        let duration = 0.6;
        let mut counts = Counts::default();
        let (end, phi) =
            propagate_with_stm(&model, law, &y0, duration, &TIGHT, &mut counts).unwrap();
        let alone = propagate(&model, law, &y0, duration, &TIGHT, &mut counts).unwrap();
        for (a, b) in end.to_array().iter().zip(alone.to_array()) {
            assert!((a - b).abs() < 1e-10 * (1.0 + b.abs()), "the same flow");
        }
        // The throttle starts on its ramp (|S| < ε) and leaves it for full thrust on the way.
        assert!(model.switching(&y0).abs() < 0.3 && model.switching(&end) < -0.3);
        assert_stm_is_the_flows_derivative(&model, law, &y0, duration, &phi);
    }
}
