//! The serialized form of a generated `NameState`: its named fields (`"q": {"beta": ..}`), not
//! the flat copy of the same values, which deserialization rebuilds from them.

use crate::kin::Health;
use crate::solvers::newton::SolveReport;

/// A generated state's named fields: inputs `I`, unknowns `U` with their analogs `UV`, `UA`,
/// outputs `O` with theirs `OV`, `OA`, and the solve's report and health. A generated state
/// serializes through it (`serde(into, from)`), so a state's JSON names every value. Every
/// number within is written and read as `crate::floats_serde` writes and reads it (each field
/// through its `within` adapter, whatever the field's type, as the generated state's own impl
/// hands the whole through it too), so that a state's NaN and infinities read back as they were.
/// A field it does not have is an error naming it, as in the generated structs within.
#[derive(Clone, Copy, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize), serde(deny_unknown_fields))]
#[cfg_attr(
    feature = "serde",
    serde(bound(
        serialize = "I: serde::Serialize, U: serde::Serialize, UV: serde::Serialize, UA: serde::Serialize, \
                 O: serde::Serialize, OV: serde::Serialize, OA: serde::Serialize",
        deserialize = "I: serde::Deserialize<'de>, U: serde::Deserialize<'de>, UV: serde::Deserialize<'de>, \
                   UA: serde::Deserialize<'de>, O: serde::Deserialize<'de>, OV: serde::Deserialize<'de>, \
                   OA: serde::Deserialize<'de>"
    ))
)]
pub struct StateByName<I, U, UV, UA, O, OV, OA> {
    /// The input values.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde::within"))]
    pub input: I,
    /// Positions of the unknowns.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde::within"))]
    pub q: U,
    /// Velocity analogs.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde::within"))]
    pub dq: UV,
    /// Acceleration analogs.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde::within"))]
    pub d2q: UA,
    /// Output values.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde::within"))]
    pub out: O,
    /// Velocity analogs of the outputs.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde::within"))]
    pub dout: OV,
    /// Acceleration analogs of the outputs.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde::within"))]
    pub d2out: OA,
    /// Diagnostics of the position solve.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde::within"))]
    pub report: SolveReport,
    /// Conditioning and assembly mode of each block.
    #[cfg_attr(feature = "serde", serde(with = "crate::floats_serde::within"))]
    pub health: Health,
}

/// The conversions of a generated state to and from its [`StateByName`]: `one` input (analogs
/// are numbers) or `many` (analogs are the named inputs' structs).
#[doc(hidden)]
#[macro_export]
macro_rules! __state_by_name {
    ($state:ident, $inputs:ident, $unknowns:ident, $outputs:ident, $n:literal, $ni:literal, $no:literal, one) => {
        $crate::__state_by_name!(@impl $state, $inputs, $unknowns, $outputs, $n, $ni, $no,
            ::core::primitive::f64, ::core::primitive::f64,
            |__v: ::core::primitive::f64| [__v], |__a: ::core::primitive::f64| [[__a]]);
    };
    ($state:ident, $inputs:ident, $unknowns:ident, $outputs:ident, $n:literal, $ni:literal, $no:literal, many) => {
        $crate::__state_by_name!(@impl $state, $inputs, $unknowns, $outputs, $n, $ni, $no,
            $inputs<::core::primitive::f64>, $inputs<$inputs<::core::primitive::f64>>,
            <[::core::primitive::f64; $ni] as ::core::convert::From<_>>::from,
            |__a: $inputs<$inputs<::core::primitive::f64>>| {
                <[$inputs<::core::primitive::f64>; $ni] as ::core::convert::From<_>>::from(__a)
                    .map(<[::core::primitive::f64; $ni] as ::core::convert::From<_>>::from)
            });
    };
    (@impl $state:ident, $inputs:ident, $unknowns:ident, $outputs:ident, $n:literal, $ni:literal, $no:literal,
        $v:ty, $a:ty, $back_v:expr, $back_a:expr) => {
        impl ::core::convert::From<$state>
            for $crate::generated::StateByName<$inputs, $unknowns, $unknowns<$v>, $unknowns<$a>, $outputs, $outputs<$v>, $outputs<$a>>
        {
            fn from(__s: $state) -> Self {
                $crate::generated::StateByName {
                    input: __s.input, q: __s.q, dq: __s.dq, d2q: __s.d2q, out: __s.out, dout: __s.dout, d2out: __s.d2out,
                    report: __s.report, health: __s.health,
                }
            }
        }
        impl ::core::convert::From<$crate::generated::StateByName<$inputs, $unknowns, $unknowns<$v>, $unknowns<$a>, $outputs, $outputs<$v>, $outputs<$a>>>
            for $state
        {
            fn from(
                __s: $crate::generated::StateByName<$inputs, $unknowns, $unknowns<$v>, $unknowns<$a>, $outputs, $outputs<$v>, $outputs<$a>>,
            ) -> Self {
                <$state as ::core::convert::From<_>>::from($crate::Kin::<$n, $ni, $no> {
                    x: ::core::convert::Into::into(__s.input),
                    q: ::core::convert::Into::into(__s.q),
                    dq: <[$v; $n] as ::core::convert::From<_>>::from(__s.dq).map($back_v),
                    d2q: <[$a; $n] as ::core::convert::From<_>>::from(__s.d2q).map($back_a),
                    out: ::core::convert::Into::into(__s.out),
                    dout: <[$v; $no] as ::core::convert::From<_>>::from(__s.dout).map($back_v),
                    d2out: <[$a; $no] as ::core::convert::From<_>>::from(__s.d2out).map($back_a),
                    report: __s.report,
                    health: __s.health,
                })
            }
        }
    };
}
