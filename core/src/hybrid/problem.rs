//! The hybrid transfer's request: what to optimise, the impulse, the engines, the arrival point
//! on the halo orbit and the costates to start from (designed on the ground); and the reasons
//! a request is refused before planning, each naming the field, the value and the limit.

use crate::contract::SettingError;
use serde::{Deserialize, Serialize};

/// What the transfer minimises.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Objective {
    /// Least propellant at a fixed time of flight: the bang-bang law (ε = 0).
    #[default]
    MinFuel = 0,
    /// Least thrust energy at a fixed time of flight (ε = 1): the homotopy's first rung.
    MinEnergy = 1,
    /// Least time of flight at full thrust (the time of flight is an unknown; the request's
    /// `duration_days` is its first guess).
    MinTime = 2,
}

impl Objective {
    /// The name in fixtures, reports and options (`min-fuel`, `min-energy`, `min-time`).
    pub const fn name(self) -> &'static str {
        match self {
            Self::MinFuel => "min-fuel",
            Self::MinEnergy => "min-energy",
            Self::MinTime => "min-time",
        }
    }
}

/// A transfer from the parking orbit through the chemical impulse to a point of the halo orbit,
/// in the paper's units (`hybrid::units`: LU the Earth–Moon distance, TU, MU the 3000 kg
/// before the impulse).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Problem {
    /// What to minimise.
    pub objective: Objective,
    /// Impulse ratio κ (speed after / before), in [1, √2).
    pub kappa: f64,
    /// Phase of the impulse on the parking orbit, rad.
    pub theta_rad: f64,
    /// κ free, by its transversality condition (minimum fuel or energy only).
    pub free_kappa: bool,
    /// θ free, by its transversality condition (minimum fuel or energy only).
    pub free_theta: bool,
    /// Time of flight, days (for minimum time, its first guess).
    pub duration_days: f64,
    /// Largest thrust of the electric engine, N.
    pub thrust_n: f64,
    /// Specific impulse of the electric engine, s.
    pub specific_impulse_s: f64,
    /// Specific impulse of the chemical engine, s.
    pub chemical_specific_impulse_s: f64,
    /// Radius of the circular parking orbit about the Earth, km.
    pub parking_radius_km: f64,
    /// Added to the state after the impulse: a navigation update of the departure, position
    /// (LU), velocity (LU/TU), mass (MU); zero for the planned departure.
    pub departure_offset: [f64; 7],
    /// Arrival position on the halo orbit, LU (rotating frame, barycentric).
    pub arrival_r_lu: [f64; 3],
    /// Arrival velocity, LU/TU.
    pub arrival_v_vu: [f64; 3],
    /// Period of the halo orbit through the arrival point, TU: the request is refused when the
    /// point does not return to itself after it (`Settings::halo_closure_tol`).
    pub halo_period_tu: f64,
    /// Initial costates to start the shooting from, `[λr, λv, λm]` (from the ground's design).
    pub costates: [f64; 7],
    /// The cost multiplier λ0 of minimum time (its unknowns `[λ0, λ]` are normalised on the
    /// unit sphere); unused by the fixed-time objectives.
    pub cost_multiplier: f64,
    /// The time of flight the start costates were designed for, days (the request's own when
    /// they were designed for it; unused by minimum time). Where the shooting does not converge
    /// from the start, the solve walks from the design to the request (docs/hybrid.md, "On
    /// board").
    pub design_duration_days: f64,
    /// The thrust the start costates were designed for, N (a derated engine: the request's is
    /// lower).
    pub design_thrust_n: f64,
}

/// A field of the request (a setting is named by its [`super::SettingId`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Field {
    /// `Problem::kappa`.
    Kappa = 0,
    /// `Problem::theta_rad`.
    Theta = 1,
    /// `Problem::duration_days`.
    Duration = 2,
    /// `Problem::thrust_n`.
    Thrust = 3,
    /// `Problem::specific_impulse_s`.
    SpecificImpulse = 4,
    /// `Problem::chemical_specific_impulse_s`.
    ChemicalSpecificImpulse = 5,
    /// `Problem::parking_radius_km`.
    ParkingRadius = 6,
    /// `Problem::departure_offset[index]`.
    DepartureOffset = 7,
    /// `Problem::arrival_r_lu[index]`.
    ArrivalPosition = 8,
    /// `Problem::arrival_v_vu[index]`.
    ArrivalVelocity = 9,
    /// `Problem::halo_period_tu`.
    HaloPeriod = 10,
    /// `Problem::costates[index]`.
    Costates = 11,
    /// `Problem::cost_multiplier`.
    CostMultiplier = 12,
    /// `Problem::free_kappa` (1 when on).
    FreeKappa = 13,
    /// `Problem::free_theta` (1 when on).
    FreeTheta = 14,
    /// `Problem::design_duration_days`.
    DesignDuration = 15,
    /// `Problem::design_thrust_n`.
    DesignThrust = 16,
}

/// A request the planner refuses.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum PlanError {
    /// A value is NaN, infinite or outside its range (`index`: the component, else 0).
    OutOfRange {
        /// Which field.
        field: Field,
        /// Component index, else 0.
        index: u8,
        /// The value given.
        value: f64,
        /// Smallest accepted.
        min: f64,
        /// Largest accepted (itself refused when `max_open`).
        max: f64,
        /// The largest value is itself refused.
        max_open: bool,
    },
    /// The arrival point does not return to itself after `halo_period_tu` (ballistic flight):
    /// the largest component of the miss, and the tolerance (`Settings::halo_closure_tol`).
    NotOnPeriodicOrbit {
        /// Largest component of `x(period) − x(0)`, LU or LU/TU.
        miss: f64,
        /// The tolerance.
        limit: f64,
    },
    /// The flight over one halo period, to check the arrival point, used up its share of the
    /// work budget (or met a singularity) before its end.
    HaloCheckUnfinished,
    /// A setting is out of its range: the setting, the value and the range.
    InvalidSetting(SettingError<super::SettingId>),
}

impl core::fmt::Display for PlanError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::OutOfRange {
                field,
                index,
                value,
                min,
                max,
                max_open,
            } => {
                let close = if *max_open { ")" } else { "]" };
                write!(
                    f,
                    "{field:?}[{index}] = {value} is outside [{min}, {max}{close} (or not finite)"
                )
            }
            Self::NotOnPeriodicOrbit { miss, limit } => write!(
                f,
                "the arrival point misses itself by {miss} after halo_period_tu, above the \
                 tolerance {limit}: not on a periodic orbit"
            ),
            Self::HaloCheckUnfinished => write!(
                f,
                "the flight over halo_period_tu that checks the arrival point did not finish \
                 within its share of the work budget"
            ),
            Self::InvalidSetting(e) => write!(f, "{e}"),
        }
    }
}

/// Check `value` in `[min, max]` (`[min, max)` when `max_open`) and finite.
fn check(
    field: Field,
    index: u8,
    value: f64,
    min: f64,
    max: f64,
    max_open: bool,
) -> Result<(), PlanError> {
    let below_max = if max_open { value < max } else { value <= max };
    if value.is_finite() && value >= min && below_max {
        Ok(())
    } else {
        Err(PlanError::OutOfRange {
            field,
            index,
            value,
            min,
            max,
            max_open,
        })
    }
}

/// Check every component of `values` in `[-bound, bound]`.
fn check_all(field: Field, values: &[f64], bound: f64) -> Result<(), PlanError> {
    for (index, &value) in (0u8..).zip(values) {
        check(field, index, value, -bound, bound, false)?;
    }
    Ok(())
}

/// The largest costate or multiplier magnitude accepted (a start beyond it is not a design).
pub const MAX_COSTATE: f64 = 1e6;

impl Problem {
    /// Check every field against its range; the minimum-time objective has no free impulse.
    ///
    /// # Errors
    /// The first [`PlanError::OutOfRange`], in declaration order.
    pub fn validate(&self) -> Result<(), PlanError> {
        check(
            Field::Kappa,
            0,
            self.kappa,
            1.0,
            core::f64::consts::SQRT_2,
            true,
        )?;
        let turn = 2.0 * core::f64::consts::PI;
        check(Field::Theta, 0, self.theta_rad, -turn, turn, false)?;
        check(Field::Duration, 0, self.duration_days, 0.1, 100.0, false)?;
        check(Field::Thrust, 0, self.thrust_n, 1e-3, 1e3, false)?;
        check(
            Field::DesignDuration,
            0,
            self.design_duration_days,
            0.1,
            100.0,
            false,
        )?;
        check(
            Field::DesignThrust,
            0,
            self.design_thrust_n,
            1e-3,
            1e3,
            false,
        )?;
        check(
            Field::SpecificImpulse,
            0,
            self.specific_impulse_s,
            100.0,
            1e5,
            false,
        )?;
        check(
            Field::ChemicalSpecificImpulse,
            0,
            self.chemical_specific_impulse_s,
            50.0,
            1000.0,
            false,
        )?;
        check(
            Field::ParkingRadius,
            0,
            self.parking_radius_km,
            6478.0,
            50_000.0,
            false,
        )?;
        // A navigation update, not another departure: 0.01 LU (3844 km), 0.1 LU/TU (102 m/s),
        // 0.1 MU (300 kg).
        let (position, rest) = self.departure_offset.split_at(3);
        check_all(Field::DepartureOffset, position, 1e-2)?;
        for (index, &value) in (3u8..).zip(rest) {
            check(Field::DepartureOffset, index, value, -0.1, 0.1, false)?;
        }
        check_all(Field::ArrivalPosition, &self.arrival_r_lu, 2.0)?;
        check_all(Field::ArrivalVelocity, &self.arrival_v_vu, 2.0)?;
        check(Field::HaloPeriod, 0, self.halo_period_tu, 0.1, 20.0, false)?;
        check_all(Field::Costates, &self.costates, MAX_COSTATE)?;
        // Unused by the fixed-time objectives, but a request with a non-finite number in it is
        // refused whatever the field.
        check_all(Field::CostMultiplier, &[self.cost_multiplier], MAX_COSTATE)?;
        if self.objective == Objective::MinTime {
            check(
                Field::CostMultiplier,
                0,
                self.cost_multiplier,
                0.0,
                MAX_COSTATE,
                false,
            )?;
            let flag = |on: bool| if on { 1.0 } else { 0.0 };
            check(Field::FreeKappa, 0, flag(self.free_kappa), 0.0, 0.0, false)?;
            check(Field::FreeTheta, 0, flag(self.free_theta), 0.0, 0.0, false)?;
        }
        Ok(())
    }
}
