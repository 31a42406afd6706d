//! One table per planner's settings: each setting is declared once, with its type, default,
//! unit, accepted range and service-limit rule, by [`settings_table!`](crate::settings_table).
//! The struct, its `Default`, the range checks, the setting names (fixture keys, limits-file
//! keys and refusal names alike), the limits check and the generic accessors the C mirror is
//! tested with all follow from that one line.

use super::PlannerKind;
use serde::{Deserialize, Serialize};

/// A setting's identity, for the refusals that name it: a planner's settings id (written by
/// [`settings_table!`](crate::settings_table)) and the request path's name of any planner's
/// setting (`limits::Setting`) both are one.
pub trait SettingName: Copy {
    /// The setting's name: its field, fixture key and limits-file key.
    fn setting_name(self) -> &'static str;
}

/// A planner's settings id: its planner and its code within that planner's table.
pub trait SettingId: SettingName {
    /// The planner the settings table belongs to.
    const PLANNER: PlannerKind;
    /// The setting's stable wire and C code within its planner.
    fn code(self) -> u8;
}

/// How a value must relate to its limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[repr(u8)]
pub enum Rule {
    /// At most the limit (loop bounds, tolerances).
    AtMost = 0,
    /// At least the limit (margins and singularity thresholds).
    AtLeast = 1,
    /// Must be on (a safety check); value and limit are 0 (off) or 1 (on).
    MustBeOn = 2,
    /// Must be off (extra work the limits do not allow); value and limit are 0 or 1.
    MustBeOff = 3,
    /// Strictly below the limit (an eccentricity below 1).
    Below = 4,
}

/// A request outside the limits: which setting (`S`: a planner's settings id, or the request
/// path's `limits::Setting`), the requested value, the limit and the rule. Integers and flags
/// are carried as `f64` (exact up to 2^53; flags as 0 / 1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct LimitViolation<S> {
    /// The setting.
    pub setting: S,
    /// The value the request asked for.
    pub value: f64,
    /// The limit it broke.
    pub limit: f64,
    /// How the value must relate to the limit.
    pub rule: Rule,
}

impl<S> LimitViolation<S> {
    /// The same violation, its setting named by `name` (a planner's id as the request path's
    /// setting).
    pub fn naming<T>(self, name: impl FnOnce(S) -> T) -> LimitViolation<T> {
        LimitViolation {
            setting: name(self.setting),
            value: self.value,
            limit: self.limit,
            rule: self.rule,
        }
    }
}

impl<S: SettingName> core::fmt::Display for LimitViolation<S> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let name = self.setting.setting_name();
        let onoff = |v: f64| if v > 0.5 { "on" } else { "off" };
        match self.rule {
            Rule::AtMost => write!(
                f,
                "{name} = {} is above the limit {}",
                self.value, self.limit
            ),
            Rule::AtLeast => write!(
                f,
                "{name} = {} is below the limit {}",
                self.value, self.limit
            ),
            Rule::Below => write!(
                f,
                "{name} = {} is not below the limit {}",
                self.value, self.limit
            ),
            Rule::MustBeOn | Rule::MustBeOff => write!(
                f,
                "{name} = {}: the limits require it {}",
                onoff(self.value),
                onoff(self.limit)
            ),
        }
    }
}

impl<S: SettingName + core::fmt::Debug> core::error::Error for LimitViolation<S> {}

/// The values a setting may take: finite, and between `min` and `max`, each end open or
/// closed. `f64::MAX` stands for "no upper end" (a range never holds an infinity, so a refusal
/// that carries one stays finite).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Range {
    /// Lower end.
    pub min: f64,
    /// Upper end.
    pub max: f64,
    /// `min` itself is refused.
    pub min_open: bool,
    /// `max` itself is refused.
    pub max_open: bool,
}

impl Range {
    /// `[min, max]`.
    pub const fn closed(min: f64, max: f64) -> Self {
        Self {
            min,
            max,
            min_open: false,
            max_open: false,
        }
    }

    /// `(min, max]`.
    pub const fn open_closed(min: f64, max: f64) -> Self {
        Self {
            min,
            max,
            min_open: true,
            max_open: false,
        }
    }

    /// `(min, max)`.
    pub const fn open(min: f64, max: f64) -> Self {
        Self {
            min,
            max,
            min_open: true,
            max_open: true,
        }
    }

    /// `[min, max)`.
    pub const fn closed_open(min: f64, max: f64) -> Self {
        Self {
            min,
            max,
            min_open: false,
            max_open: true,
        }
    }

    /// Finite and above zero: `(0, MAX]`.
    pub const fn positive() -> Self {
        Self::open_closed(0.0, f64::MAX)
    }

    /// Finite and at least `min`: `[min, MAX]`.
    pub const fn at_least(min: f64) -> Self {
        Self::closed(min, f64::MAX)
    }

    /// Any finite value (flags, codes, seeds: their type alone restricts them).
    pub const fn any() -> Self {
        Self::closed(-f64::MAX, f64::MAX)
    }

    /// `value` is finite and inside the range.
    pub fn contains(&self, value: f64) -> bool {
        let above_min = if self.min_open {
            value > self.min
        } else {
            value >= self.min
        };
        let below_max = if self.max_open {
            value < self.max
        } else {
            value <= self.max
        };
        value.is_finite() && above_min && below_max
    }
}

impl core::fmt::Display for Range {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let open = if self.min_open { '(' } else { '[' };
        let close = if self.max_open { ')' } else { ']' };
        if self.max >= f64::MAX {
            write!(f, "{open}{}, no upper end{close}", self.min)
        } else {
            write!(f, "{open}{}, {}{close}", self.min, self.max)
        }
    }
}

/// A setting outside its accepted range: which setting, the value given (as the caller gave
/// it: a NaN stays NaN) and the range it must be in.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SettingError<S> {
    /// The setting (its planner's settings id).
    pub setting: S,
    /// The value given.
    pub value: f64,
    /// The values accepted.
    pub range: Range,
}

impl<S: SettingName> core::fmt::Display for SettingError<S> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "setting {} = {} is outside {}",
            self.setting.setting_name(),
            self.value,
            self.range
        )
    }
}

impl<S: SettingName + core::fmt::Debug> core::error::Error for SettingError<S> {}

/// Check `value` of `setting` against `range`.
///
/// # Errors
/// [`SettingError`] when `value` is not finite or outside the range.
pub fn check_range<S>(setting: S, value: f64, range: Range) -> Result<(), SettingError<S>> {
    if range.contains(value) {
        Ok(())
    } else {
        Err(SettingError {
            setting,
            value,
            range,
        })
    }
}

/// Check `value` of `setting` against its service limit by `rule`.
///
/// # Errors
/// [`LimitViolation`] when the value is on the wrong side of the limit. A NaN or an infinity,
/// in the value or the limit, passes here: a violation carries finite numbers only (an answer
/// has no NaN or infinity, issue 29), and the planner's own validation names a non-finite
/// value the request gave (a setting by its range, a problem number by its field).
pub fn check_limit<S>(
    setting: S,
    rule: Rule,
    value: f64,
    limit: f64,
) -> Result<(), LimitViolation<S>> {
    if !(value.is_finite() && limit.is_finite()) {
        return Ok(());
    }
    let broken = match rule {
        Rule::AtMost => value > limit,
        Rule::AtLeast => value < limit,
        Rule::Below => value >= limit,
        Rule::MustBeOn => limit > 0.5 && value < 0.5,
        Rule::MustBeOff => limit < 0.5 && value > 0.5,
    };
    if broken {
        Err(LimitViolation {
            setting,
            value,
            limit,
            rule,
        })
    } else {
        Ok(())
    }
}

/// A setting's value as a number (for range checks, limits, refusals and the C mirror's
/// coverage test) and back.
pub trait SettingValue: Copy {
    /// The value as `f64` (flags 0 / 1, enumerations their code; integers exact below 2^53).
    fn to_f64(self) -> f64;
    /// The value from `f64`, or `None` when no value of the type is that number.
    fn from_f64(value: f64) -> Option<Self>;
}

/// `value` is a whole number (no fractional part, finite).
fn whole(value: f64) -> bool {
    value.is_finite() && libm::fabs(value - libm::trunc(value)) <= 0.0
}

macro_rules! setting_value_int {
    ($($t:ty),*) => {$(
        impl SettingValue for $t {
            // Exact below 2^53, far above every setting's range.
            #[allow(clippy::cast_precision_loss)]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            fn from_f64(value: f64) -> Option<Self> {
                // `<=` on the upper end: `MAX as f64` may round up to a value one above MAX,
                // which the saturating cast then clamps (u64 only; exact for the others).
                (whole(value) && value >= <$t>::MIN as f64 && value <= <$t>::MAX as f64)
                    .then_some(value as $t)
            }
        }
    )*};
}
setting_value_int!(u8, u16, u32, u64, i32);

impl SettingValue for f64 {
    fn to_f64(self) -> f64 {
        self
    }
    fn from_f64(value: f64) -> Option<Self> {
        Some(value)
    }
}

impl SettingValue for bool {
    fn to_f64(self) -> f64 {
        if self {
            1.0
        } else {
            0.0
        }
    }
    fn from_f64(value: f64) -> Option<Self> {
        if !whole(value) {
            None
        } else if value < 0.5 && value > -0.5 {
            Some(false)
        } else if value > 0.5 && value < 1.5 {
            Some(true)
        } else {
            None
        }
    }
}

/// Declare a planner's settings once (see the module docs). Each line:
///
/// ```text
/// /// Doc comment (the field's, the C mirror's and the refusals' meaning).
/// field_name, VariantName = code: Type = default, unit "unit", range RANGE, limit RULE;
/// ```
///
/// `RANGE` is a [`Range`] expression (checked by the generated `check_ranges`, in declaration
/// order); `RULE` is `AtMost`, `AtLeast`, `MustBeOn`, `MustBeOff` (the service limit: the
/// default limits are the default settings) or `Free` (no limit: the setting chooses the
/// problem or the method, not the amount of work or safety). `code` is the setting's stable
/// wire and C code within its planner. Generates the settings struct (serde keys = the field
/// names), `Default`, the id enum with `ALL`, `name`, `unit`, `range`, `limit_rule`, and on
/// the struct `value`, `set`, `check_ranges` and `check_limits`.
#[macro_export]
macro_rules! settings_table {
    (
        $(#[$smeta:meta])*
        pub struct $Settings:ident;
        $(#[$imeta:meta])*
        pub enum $Id:ident for $kind:ident;
        {
            $(
                $(#[$fmeta:meta])*
                $field:ident, $Var:ident = $code:literal : $ty:ty = $default:expr,
                unit $unit:literal, range $range:expr, limit $rule:ident;
            )+
        }
    ) => {
        $(#[$smeta])*
        #[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
        pub struct $Settings {
            $(
                $(#[$fmeta])*
                pub $field: $ty,
            )+
        }

        impl $Settings {
            /// The defaults, as a constant (a flight image's limits can then sit in flash).
            pub const DEFAULT: Self = Self {
                $( $field: $default, )+
            };
        }

        impl Default for $Settings {
            fn default() -> Self {
                Self::DEFAULT
            }
        }

        $(#[$imeta])*
        #[derive(
            Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash,
            serde::Serialize, serde::Deserialize,
        )]
        #[repr(u8)]
        pub enum $Id {
            $(
                #[doc = concat!("`", stringify!($field), "` (", $unit, ")")]
                $Var = $code,
            )+
        }

        impl $Id {
            /// Every setting, in declaration order.
            pub const ALL: &'static [Self] = &[ $( Self::$Var, )+ ];

            /// The setting's name: its field, its fixture key, its limits-file key.
            pub const fn name(self) -> &'static str {
                match self {
                    $( Self::$Var => stringify!($field), )+
                }
            }

            /// The setting's unit ("" for counts, flags and dimensionless tolerances).
            pub const fn unit(self) -> &'static str {
                match self {
                    $( Self::$Var => $unit, )+
                }
            }

            /// The values the planner accepts.
            pub const fn range(self) -> $crate::contract::Range {
                match self {
                    $( Self::$Var => $range, )+
                }
            }

            /// How a request's value must relate to the service limit, or `None` when the
            /// setting has no limit.
            pub const fn limit_rule(self) -> Option<$crate::contract::Rule> {
                match self {
                    $( Self::$Var => $crate::settings_table!(@rule $rule), )+
                }
            }

            /// The setting of this code, if any.
            pub const fn from_code(code: u8) -> Option<Self> {
                match code {
                    $( $code => Some(Self::$Var), )+
                    _ => None,
                }
            }
        }

        impl $crate::contract::SettingName for $Id {
            fn setting_name(self) -> &'static str {
                self.name()
            }
        }

        impl $crate::contract::SettingId for $Id {
            const PLANNER: $crate::contract::PlannerKind = $crate::contract::PlannerKind::$kind;
            fn code(self) -> u8 {
                self as u8
            }
        }

        impl $Settings {
            /// The value of setting `id` as a number (flags 0 / 1, enumerations their code).
            pub fn value(&self, id: $Id) -> f64 {
                match id {
                    $( $Id::$Var => $crate::contract::SettingValue::to_f64(self.$field), )+
                }
            }

            /// Set setting `id` from a number; `false` (nothing changed) when no value of the
            /// field's type is that number.
            pub fn set(&mut self, id: $Id, value: f64) -> bool {
                match id {
                    $(
                        $Id::$Var => match $crate::contract::SettingValue::from_f64(value) {
                            Some(v) => {
                                self.$field = v;
                                true
                            }
                            None => false,
                        },
                    )+
                }
            }

            /// Check every setting against its range, in declaration order.
            ///
            /// # Errors
            /// The first [`SettingError`](crate::contract::SettingError).
            pub fn check_ranges(&self) -> Result<(), $crate::contract::SettingError<$Id>> {
                $(
                    $crate::contract::check_range(
                        $Id::$Var,
                        $crate::contract::SettingValue::to_f64(self.$field),
                        $range,
                    )?;
                )+
                Ok(())
            }

            /// Check every limited setting against `limits` (the service's limits, written as
            /// settings: the most work, the least safety a request may ask for), in
            /// declaration order.
            ///
            /// # Errors
            /// The first [`LimitViolation`](crate::contract::LimitViolation).
            pub fn check_limits(
                &self,
                limits: &Self,
            ) -> Result<(), $crate::contract::LimitViolation<$Id>> {
                for &id in $Id::ALL {
                    if let Some(rule) = id.limit_rule() {
                        $crate::contract::check_limit(
                            id,
                            rule,
                            self.value(id),
                            limits.value(id),
                        )?;
                    }
                }
                Ok(())
            }
        }
    };
    (@rule AtMost) => { Some($crate::contract::Rule::AtMost) };
    (@rule AtLeast) => { Some($crate::contract::Rule::AtLeast) };
    (@rule MustBeOn) => { Some($crate::contract::Rule::MustBeOn) };
    (@rule MustBeOff) => { Some($crate::contract::Rule::MustBeOff) };
    (@rule Free) => { None };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_limit_violation_carries_finite_numbers_only() {
        // Issue 29 (finite answers): a NaN or an infinity on either side passes the limits;
        // the planner's validation names the request's (tests/finite_answers.rs).
        let s = crate::limits::Setting::Problem(crate::limits::ProblemLimit::ChiefEccentricity);
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for rule in [Rule::AtMost, Rule::AtLeast, Rule::Below] {
                assert_eq!(check_limit(s, rule, x, 1.0), Ok(()));
                assert_eq!(check_limit(s, rule, 1.0, x), Ok(()));
            }
        }
        let e = check_limit(s, Rule::Below, 1.5, 1.0).unwrap_err();
        assert_eq!((e.value, e.limit, e.rule), (1.5, 1.0, Rule::Below));
        assert!(check_limit(s, Rule::AtMost, f64::MAX, 1.0).is_err());
    }

    #[test]
    fn ranges_refuse_non_finite_and_open_ends() {
        assert!(Range::positive().contains(1e-300));
        assert!(!Range::positive().contains(0.0));
        assert!(!Range::positive().contains(f64::NAN));
        assert!(!Range::positive().contains(f64::INFINITY));
        assert!(Range::closed(1.0, 2.0).contains(2.0));
        assert!(!Range::closed_open(1.0, 2.0).contains(2.0));
        assert!(Range::any().contains(-1e300));
        let e = check_range(
            crate::pseudospectral::SettingId::VerifyTolLu,
            f64::NAN,
            Range::positive(),
        )
        .unwrap_err();
        assert!(e.value.is_nan());
        assert_eq!(e.range.max, f64::MAX);
    }

    #[test]
    fn values_round_trip_through_numbers() {
        assert_eq!(u8::from_f64(255.0), Some(255));
        assert_eq!(u8::from_f64(256.0), None);
        assert_eq!(u16::from_f64(1.5), None);
        assert_eq!(i32::from_f64(-3.0), Some(-3));
        assert_eq!(u64::from_f64(4e7), Some(40_000_000));
        assert_eq!(bool::from_f64(1.0), Some(true));
        assert_eq!(bool::from_f64(2.0), None);
        assert_eq!(true.to_f64(), 1.0);
    }
}
