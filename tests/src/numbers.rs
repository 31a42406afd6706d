//! Every number of a serialisable value, by path: a serde [`Serializer`](serde::Serializer)
//! that writes nothing and records each `f32` / `f64` it is shown with the path of fields,
//! variants and indices that leads to it. The finite-answers property test walks every
//! outcome with it (serde_json would hide a NaN: it writes `null`).

use serde::ser::{self, Serialize};
use std::fmt;

/// A number met by the walk: its path (`LeoArc.burns[1].dv_km_s[2]`) and its value.
#[derive(Clone, Debug, PartialEq)]
pub struct Number {
    /// Fields (`.name`), variants (`Name`) and indices (`[i]`) from the root.
    pub path: String,
    /// The value.
    pub value: f64,
}

/// Every floating-point number of `value`, in serialisation order.
pub fn numbers<T: Serialize + ?Sized>(value: &T) -> Vec<Number> {
    let mut walker = Walker::default();
    // The walker's serialisation never fails: its error type exists for the trait only.
    match value.serialize(&mut walker) {
        Ok(()) | Err(WalkError) => walker.found,
    }
}

/// The numbers of `value` that are NaN or infinite.
pub fn non_finite<T: Serialize + ?Sized>(value: &T) -> Vec<Number> {
    numbers(value)
        .into_iter()
        .filter(|n| !n.value.is_finite())
        .collect()
}

#[derive(Default)]
struct Walker {
    path: Vec<String>,
    /// The index of the next element of each open sequence (innermost last).
    index: Vec<usize>,
    found: Vec<Number>,
}

impl Walker {
    fn record(&mut self, value: f64) {
        self.found.push(Number {
            path: self.path.concat(),
            value,
        });
    }

    fn element<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), WalkError> {
        let i = self.index.last().copied().unwrap_or(0);
        if let Some(last) = self.index.last_mut() {
            *last += 1;
        }
        self.path.push(format!("[{i}]"));
        let r = value.serialize(&mut *self);
        self.path.pop();
        r
    }

    fn field<T: Serialize + ?Sized>(&mut self, key: &str, value: &T) -> Result<(), WalkError> {
        self.path.push(format!(".{key}"));
        let r = value.serialize(&mut *self);
        self.path.pop();
        r
    }

    fn open(&mut self, name: &str) {
        self.path.push(name.to_owned());
        self.index.push(0);
    }

    fn close(&mut self) {
        self.path.pop();
        self.index.pop();
    }
}

/// The walk's error type (never produced by the walk itself).
#[derive(Debug)]
struct WalkError;

impl fmt::Display for WalkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("walk error")
    }
}

impl std::error::Error for WalkError {}

impl ser::Error for WalkError {
    fn custom<T: fmt::Display>(_msg: T) -> Self {
        Self
    }
}

macro_rules! ignore {
    ($($method:ident($t:ty)),* $(,)?) => {$(
        fn $method(self, _v: $t) -> Result<(), WalkError> {
            Ok(())
        }
    )*};
}

impl ser::Serializer for &mut Walker {
    type Ok = ();
    type Error = WalkError;
    type SerializeSeq = Self;
    type SerializeTuple = Self;
    type SerializeTupleStruct = Self;
    type SerializeTupleVariant = Self;
    type SerializeMap = Self;
    type SerializeStruct = Self;
    type SerializeStructVariant = Self;

    ignore!(
        serialize_bool(bool),
        serialize_i8(i8),
        serialize_i16(i16),
        serialize_i32(i32),
        serialize_i64(i64),
        serialize_i128(i128),
        serialize_u8(u8),
        serialize_u16(u16),
        serialize_u32(u32),
        serialize_u64(u64),
        serialize_u128(u128),
        serialize_char(char),
        serialize_str(&str),
        serialize_bytes(&[u8]),
        serialize_unit_struct(&'static str),
    );

    fn serialize_f32(self, v: f32) -> Result<(), WalkError> {
        self.record(f64::from(v));
        Ok(())
    }

    fn serialize_f64(self, v: f64) -> Result<(), WalkError> {
        self.record(v);
        Ok(())
    }

    fn serialize_none(self) -> Result<(), WalkError> {
        Ok(())
    }

    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), WalkError> {
        value.serialize(self)
    }

    fn serialize_unit(self) -> Result<(), WalkError> {
        Ok(())
    }

    fn serialize_unit_variant(
        self,
        _name: &'static str,
        _index: u32,
        _variant: &'static str,
    ) -> Result<(), WalkError> {
        Ok(())
    }

    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        value: &T,
    ) -> Result<(), WalkError> {
        value.serialize(self)
    }

    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
        value: &T,
    ) -> Result<(), WalkError> {
        self.path.push(variant.to_owned());
        let r = value.serialize(&mut *self);
        self.path.pop();
        r
    }

    fn serialize_seq(self, _len: Option<usize>) -> Result<Self, WalkError> {
        self.open("");
        Ok(self)
    }

    fn serialize_tuple(self, _len: usize) -> Result<Self, WalkError> {
        self.open("");
        Ok(self)
    }

    fn serialize_tuple_struct(self, _name: &'static str, _len: usize) -> Result<Self, WalkError> {
        self.open("");
        Ok(self)
    }

    fn serialize_tuple_variant(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
        _len: usize,
    ) -> Result<Self, WalkError> {
        self.open(variant);
        Ok(self)
    }

    fn serialize_map(self, _len: Option<usize>) -> Result<Self, WalkError> {
        self.open("");
        Ok(self)
    }

    fn serialize_struct(self, _name: &'static str, _len: usize) -> Result<Self, WalkError> {
        self.open("");
        Ok(self)
    }

    fn serialize_struct_variant(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
        _len: usize,
    ) -> Result<Self, WalkError> {
        self.open(variant);
        Ok(self)
    }
}

macro_rules! elements {
    ($($Trait:ident :: $method:ident),* $(,)?) => {$(
        impl ser::$Trait for &mut Walker {
            type Ok = ();
            type Error = WalkError;
            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), WalkError> {
                self.element(value)
            }
            fn end(self) -> Result<(), WalkError> {
                self.close();
                Ok(())
            }
        }
    )*};
}

elements!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field,
    SerializeTupleVariant::serialize_field,
);

macro_rules! fields {
    ($($Trait:ident),* $(,)?) => {$(
        impl ser::$Trait for &mut Walker {
            type Ok = ();
            type Error = WalkError;
            fn serialize_field<T: Serialize + ?Sized>(
                &mut self,
                key: &'static str,
                value: &T,
            ) -> Result<(), WalkError> {
                self.field(key, value)
            }
            fn end(self) -> Result<(), WalkError> {
                self.close();
                Ok(())
            }
        }
    )*};
}

fields!(SerializeStruct, SerializeStructVariant);

impl ser::SerializeMap for &mut Walker {
    type Ok = ();
    type Error = WalkError;
    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), WalkError> {
        // A map's keys are walked as its elements are: a number key is a number of the value.
        self.element(key)
    }
    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), WalkError> {
        self.element(value)
    }
    fn end(self) -> Result<(), WalkError> {
        self.close();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Serialize)]
    enum E {
        A { x: f64, v: Vec<(u8, f64)> },
        B(Option<f64>),
    }

    #[test]
    fn every_number_is_found_with_its_path() {
        let e = E::A {
            x: f64::NAN,
            v: vec![(1, 2.0), (3, f64::INFINITY)],
        };
        let found = numbers(&e);
        let paths: Vec<&str> = found.iter().map(|n| n.path.as_str()).collect();
        assert_eq!(paths, ["A.x", "A.v[0][1]", "A.v[1][1]"]);
        let bad: Vec<String> = non_finite(&e).into_iter().map(|n| n.path).collect();
        assert_eq!(bad, ["A.x", "A.v[1][1]"]);
        assert_eq!(numbers(&E::B(None)), []);
        assert_eq!(non_finite(&E::B(Some(f64::NEG_INFINITY))).len(), 1);
        assert_eq!(non_finite(&[1.0f32, f32::NAN]).len(), 1);
    }
}
