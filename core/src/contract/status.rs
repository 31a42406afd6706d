//! The status enum of a planner, written once: [`status_enum!`](crate::status_enum).

/// Define a planner's `SolveStatus`-like enum and its [`Status`](super::Status) impl from one
/// list of variants, so that the stable codes, the usable set and the budget stop are stated in
/// one place and cannot drift from the `repr(u8)` discriminants.
///
/// The enum gets `#[repr(u8)]`, the derives every status has (`Clone`, `Copy`, `Debug`,
/// `Default`, `PartialEq`, serde's two; the caller may add `#[derive(Eq)]`) and the default
/// variant `Unsolved = 0`. The caller gives the docs and the other variants, each written as in
/// an enum with its discriminant (`Solved = 1`, `Name(Stage) = 5`, `Name { field: T } = 6`).
/// After the enum:
///
/// * `usable: [<pattern>];` the variants that may be flown (the inherent `const fn is_usable`);
/// * `budget: BudgetExhausted;` when the enum has `BudgetExhausted { verified: bool }` (the
///   contract's budget stop), or `budget: none;` when it has no work budget of its own.
///
/// It also writes the inherent `const fn code`, the variant's stable code.
#[macro_export]
macro_rules! status_enum {
    (
        $(#[$meta:meta])*
        $vis:vis enum $Name:ident {
            $(
                $(#[$vmeta:meta])*
                $Variant:ident
                $( ( $($tuple:ty),* $(,)? ) )?
                $( { $( $(#[$fmeta:meta])* $field:ident : $fty:ty ),* $(,)? } )?
                = $code:literal
            ),* $(,)?
        }
        usable: [$usable:pat];
        budget: $budget:ident;
    ) => {
        #[derive(Clone, Copy, Debug, Default, PartialEq, ::serde::Serialize, ::serde::Deserialize)]
        $(#[$meta])*
        #[repr(u8)]
        $vis enum $Name {
            /// Nothing has written this outcome yet (the default).
            #[default]
            Unsolved = 0,
            $(
                $(#[$vmeta])*
                $Variant
                $( ( $($tuple),* ) )?
                $( { $( $(#[$fmeta])* $field : $fty ),* } )?
                = $code
            ),*
        }

        impl $Name {
            /// The plan may be flown (the variants the type's docs call usable).
            pub const fn is_usable(&self) -> bool {
                matches!(self, $usable)
            }

            /// The variant's stable code (its `repr(u8)` discriminant).
            // `{ .. }` matches unit, tuple and struct variants alike.
            #[allow(clippy::unneeded_struct_pattern)]
            pub const fn code(&self) -> u8 {
                match self {
                    Self::Unsolved => 0,
                    $( Self::$Variant { .. } => $code, )*
                }
            }
        }

        impl $crate::contract::Status for $Name {
            fn is_usable(&self) -> bool {
                $Name::is_usable(self)
            }

            fn code(&self) -> u8 {
                $Name::code(self)
            }

            $crate::status_enum!(@budget $budget);
        }
    };
    (@budget none) => {
        fn budget_exhausted(&self) -> Option<bool> {
            None
        }
    };
    (@budget $Budget:ident) => {
        fn budget_exhausted(&self) -> Option<bool> {
            match *self {
                Self::$Budget { verified } => Some(verified),
                _ => None,
            }
        }
    };
}
