//! The names of a mechanism's generated types.

use super::names;
use proc_macro2::Ident;
use quote::format_ident;

/// The names of the generated types of mechanism `name`.
pub struct Types {
    /// The mechanism's name as declared (the parameter struct).
    pub name: Ident,
    /// The name without `r#`, for messages and derived names.
    pub plain: String,
    /// `NameInputs`.
    pub inputs: Ident,
    /// `NameUnknowns`.
    pub unknowns: Ident,
    /// `NameOutputs`.
    pub outputs: Ident,
    /// `NameState`.
    pub state: Ident,
    /// `NameMotion`.
    pub motion: Ident,
    /// `NameColumns`: the typed column handles of `Name::COL`.
    pub columns: Ident,
    /// `NameParams` (one value per parameter, in the sensitivities).
    pub params: Ident,
    /// `NameSensitivities`.
    pub sens: Ident,
}

impl Types {
    /// The type names of mechanism `name`.
    pub fn of(name: &Ident) -> Types {
        let plain = names::plain(name);
        let t = |suffix: &str| format_ident!("{}{}", plain, suffix);
        Types {
            name: name.clone(),
            inputs: t("Inputs"),
            unknowns: t("Unknowns"),
            outputs: t("Outputs"),
            state: t("State"),
            motion: t("Motion"),
            columns: t("Columns"),
            params: t("Params"),
            sens: t("Sensitivities"),
            plain,
        }
    }
}
