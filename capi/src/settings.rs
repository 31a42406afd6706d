//! The C settings structs (`ReconfigASettings`, `ReconfigBSettings`, `ReconfigGeoSettings`,
//! `ReconfigLeoArcSettings`, `ReconfigHybridSettings`) mirror the core's settings tables field by field, under the same
//! names. Each mirror is one
//! [`mirror_settings!`](crate::mirror_settings) line listing the fields once: the conversion
//! both ways and the by-name accessors the coverage test walks follow from it. The C structs
//! themselves are written out in `types_*.rs` (cbindgen reads them there; it does not expand
//! macros). A field missing from a mirror's list fails to compile (`from_core` builds the C
//! struct with every field) or fails the coverage test (`capi/tests/settings.rs`: every
//! `SettingId` of every planner survives core -> C -> core).

use crate::status::{ReconfigError, RECONFIG_ERR_SETTING_OUT_OF_RANGE, RECONFIG_FIELD_SETTINGS};
use reconfig_core::contract::SettingValue;
use reconfig_core::impulsive::ElementSet;
use reconfig_core::leo_tour::flight::Model;
use reconfig_core::limits::Setting;

/// A C field's value as the core's field type, and back. The identity for numbers; a C `uint8_t`
/// for a flag (0 or 1) or an enumeration code.
pub trait CValue<T>: Copy {
    /// The largest C value that converts (a refusal's `limit` when `to_core` fails).
    const LARGEST: f64 = f64::MAX;
    /// The core's value, or `None` when no value of the core's type is this one.
    fn to_core(self) -> Option<T>;
    /// The C value of the core's.
    fn from_core(value: T) -> Self;
}

impl<T: Copy> CValue<T> for T {
    fn to_core(self) -> Option<T> {
        Some(self)
    }
    fn from_core(value: T) -> Self {
        value
    }
}

impl CValue<bool> for u8 {
    const LARGEST: f64 = 1.0;
    fn to_core(self) -> Option<bool> {
        match self {
            0 => Some(false),
            1 => Some(true),
            _ => None,
        }
    }
    fn from_core(value: bool) -> Self {
        u8::from(value)
    }
}

impl CValue<ElementSet> for u8 {
    const LARGEST: f64 = 1.0;
    fn to_core(self) -> Option<ElementSet> {
        ElementSet::from_f64(f64::from(self))
    }
    fn from_core(value: ElementSet) -> Self {
        value as u8
    }
}

impl CValue<Model> for u8 {
    const LARGEST: f64 = 1.0;
    fn to_core(self) -> Option<Model> {
        <Model as SettingValue>::from_f64(f64::from(self))
    }
    fn from_core(value: Model) -> Self {
        value as u8
    }
}

/// A C settings struct that mirrors a core settings table.
pub trait SettingsMirror: Copy {
    /// The core's settings.
    type Core: Default;

    /// Write every field into the core's settings, in place (the request's settings in the
    /// caller's workspace block).
    ///
    /// # Errors
    /// `RECONFIG_ERR_SETTING_OUT_OF_RANGE` naming the first field whose C value no value of the
    /// core's type is (a flag other than 0 or 1, an enumeration code outside its set):
    /// `index` the setting's code, `value` the C value, `limit` the largest code, `detail` 1.
    fn to_core(&self, out: &mut Self::Core) -> Result<(), ReconfigError>;

    /// The C struct of the core's settings.
    fn from_core(settings: &Self::Core) -> Self;

    /// The C field named `name` (the setting's name) as a number, or `None` when the struct
    /// has no such field.
    fn c_value(&self, name: &str) -> Option<f64>;

    /// Set the C field named `name` from a number; `false` when there is no such field or no
    /// value of the C type is that number.
    fn c_set(&mut self, name: &str, value: f64) -> bool;
}

/// Convert one C field, or refuse it naming the setting `name` among `all`.
///
/// # Errors
/// As [`SettingsMirror::to_core`].
pub fn convert<C, T, I>(c: C, all: &[I], name: &str) -> Result<T, ReconfigError>
where
    C: CValue<T> + SettingValue,
    I: Copy + Into<Setting>,
{
    match c.to_core() {
        Some(value) => Ok(value),
        None => Err(ReconfigError::new(
            RECONFIG_ERR_SETTING_OUT_OF_RANGE,
            RECONFIG_FIELD_SETTINGS,
            c.to_f64(),
            <C as CValue<T>>::LARGEST,
        )
        .at(code_of(all, name))
        .with_detail(1)),
    }
}

/// The code of the setting named `name` among `all` (-1 if none: the coverage test checks
/// every C field has its setting).
pub fn code_of<I: Copy + Into<Setting>>(all: &[I], name: &str) -> i32 {
    all.iter()
        .map(|&id| id.into())
        .find(|s: &Setting| s.name() == name)
        .map_or(-1, |s| i32::from(s.code()))
}

/// Declare that C struct `$C` mirrors the core's `$Core` (settings ids `$Id`), listing the
/// fields once (same names on both sides).
#[macro_export]
macro_rules! mirror_settings {
    ($C:ty => $Core:ty, $Id:ty { $($field:ident),+ $(,)? }) => {
        impl $crate::settings::SettingsMirror for $C {
            type Core = $Core;

            fn to_core(&self, out: &mut $Core) -> Result<(), $crate::status::ReconfigError> {
                $(
                    out.$field =
                        $crate::settings::convert(self.$field, <$Id>::ALL, stringify!($field))?;
                )+
                Ok(())
            }

            fn from_core(s: &$Core) -> Self {
                Self {
                    $( $field: $crate::settings::CValue::from_core(s.$field), )+
                }
            }

            fn c_value(&self, name: &str) -> Option<f64> {
                $(
                    if name == stringify!($field) {
                        return Some(reconfig_core::contract::SettingValue::to_f64(self.$field));
                    }
                )+
                None
            }

            fn c_set(&mut self, name: &str, value: f64) -> bool {
                $(
                    if name == stringify!($field) {
                        return match reconfig_core::contract::SettingValue::from_f64(value) {
                            Some(v) => {
                                self.$field = v;
                                true
                            }
                            None => false,
                        };
                    }
                )+
                false
            }
        }
    };
}
