//! What `mechanism!` implements for a declaration it rejected, next to its `compile_error!`s:
//! the whole named surface of an accepted mechanism (constants, the `Mechanism` and `Named`
//! implementations, the inherent methods), so that user code calling `m.solve(x)` or
//! `m.sweep(..)` reports nothing but the declaration's own errors.
//!
//! The kernels' bodies call [`rejected`]: a crate with a `compile_error!` never links, so none
//! of them can run; they exist only to be type-checked against the user's code.

/// The body of every kernel of a rejected declaration. Unreachable: the `compile_error!`s
/// emitted beside it stop the crate from compiling.
#[cold]
pub fn rejected() -> ! {
    unreachable!("`mechanism!` rejected this declaration at compile time: see its errors")
}

/// Why `mass_model` does not compile on a mechanism declared without masses, inertias or loads:
/// the generated `mass_model` of such a mechanism requires this trait, which no type implements.
#[diagnostic::on_unimplemented(
    message = "`{Self}` was declared without masses, inertias or loads",
    label = "`mass_model` is generated from the declared dynamics items",
    note = "declare the moving bodies in the `mechanism!` of `{Self}`, e.g. `body rod: mass m2, com s2, inertia j2, turns phi2;`, and loads (`force`, `torque`, `gravity`) where they act"
)]
pub trait MassModelDeclared<'a> {
    /// Never called: no type implements this trait.
    fn absurd(&self) -> core::convert::Infallible;
}

/// The named surface of a rejected declaration (see the module documentation): the constants,
/// `Mechanism` with kernels that are never run, `Named` and the inherent named API.
#[doc(hidden)]
#[macro_export]
macro_rules! __rejected_mechanism {
    (
        $name:ident, $inputs:ident, $unknowns:ident, $outputs:ident, $state:ident, $motion:ident,
        $n:literal, $ni:literal, $no:literal, $np:literal, $plain:literal,
        params [$($pf:ident $pidx:literal $ps:literal),*],
        inputs [$($is:literal),*], unknowns [$($us:literal),*], outputs [$($os:literal),*]
    ) => {
        impl $name {
            /// The mechanism's type name.
            pub const NAME: &'static ::core::primitive::str = $plain;
            /// Parameter names, in declaration order.
            pub const PARAMS: [&'static ::core::primitive::str; $np] = [$($ps),*];
            /// Input names.
            pub const INPUTS: [&'static ::core::primitive::str; $ni] = [$($is),*];
            /// Unknown names.
            pub const UNKNOWNS: [&'static ::core::primitive::str; $n] = [$($us),*];
            /// Scalar equation names (none known: the declaration was rejected).
            pub const EQUATIONS: [&'static ::core::primitive::str; $n] = [""; $n];
            /// Output columns.
            pub const OUTPUTS: [&'static ::core::primitive::str; $no] = [$($os),*];
            /// The decomposition (none: the declaration was rejected).
            pub const BLOCKS: &'static [$crate::BlockInfo] = &[];
            /// The decomposition in words.
            pub const DECOMPOSITION: &'static ::core::primitive::str =
                "not analysed: `mechanism!` rejected the declaration";

            /// Parameter values in declaration order.
            pub fn param_values(&self) -> [::core::primitive::f64; $np] {
                [$(self.$pf),*]
            }

            /// Builds the mechanism from parameter values in declaration order.
            pub fn from_param_values(values: [::core::primitive::f64; $np]) -> Self {
                $name { $($pf: values[$pidx]),* }
            }
        }

        impl $crate::Mechanism<$n, $ni, $no> for $name {
            $crate::__mechanism_consts!($name, $n, $ni, $no);
            fn guess_flat(&self, _: &[::core::primitive::f64; $ni]) -> [::core::primitive::f64; $n] {
                $crate::generated::rejected()
            }
            fn position_flat(
                &self,
                _: &[::core::primitive::f64; $ni],
                _: &[::core::primitive::f64; $n],
                _: &$crate::NewtonConfig,
            ) -> ::core::result::Result<([::core::primitive::f64; $n], $crate::SolveReport), $crate::Error> {
                $crate::generated::rejected()
            }
            fn kinematics_flat(
                &self,
                _: &[::core::primitive::f64; $ni],
                _: &[::core::primitive::f64; $n],
                _: &$crate::NewtonConfig,
            ) -> $crate::generated::KinResult<$n, $ni, $no> {
                $crate::generated::rejected()
            }
            fn kinematics_at_flat(
                &self,
                _: &[::core::primitive::f64; $ni],
                _: &[::core::primitive::f64; $n],
                _: &$crate::NewtonConfig,
            ) -> $crate::generated::KinResult<$n, $ni, $no> {
                $crate::generated::rejected()
            }
            fn outputs_flat(
                &self,
                _: &[::core::primitive::f64; $ni],
                _: &[::core::primitive::f64; $n],
            ) -> [::core::primitive::f64; $no] {
                $crate::generated::rejected()
            }
            fn jacobian_flat(
                &self,
                _: &[::core::primitive::f64; $ni],
                _: &[::core::primitive::f64; $n],
            ) -> $crate::Jac<$n, $ni> {
                $crate::generated::rejected()
            }
        }

        $crate::__named_api!($name, $inputs, $unknowns, $outputs, $state, $motion, $n, $ni, $no);
    };
}

/// `mass_model` of a mechanism declared without masses, inertias or loads: a method whose bound
/// no type meets ([`MassModelDeclared`]), so that calling it is a compile error saying what to
/// declare rather than "no method named `mass_model`". The bound is higher-ranked so that it is
/// checked where the method is called, not where it is defined.
#[doc(hidden)]
#[macro_export]
macro_rules! __no_mass_model {
    ($name:ident) => {
        impl $name {
            /// Not generated: declare masses, inertias or loads in the mechanism.
            #[doc(hidden)]
            pub fn mass_model(&self) -> ::core::convert::Infallible
            where
                for<'a> Self: $crate::generated::MassModelDeclared<'a>,
            {
                $crate::generated::MassModelDeclared::absurd(self)
            }
        }
    };
}
