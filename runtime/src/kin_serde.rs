//! Serialize and Deserialize of the flat kinematic state (feature `serde`). serde has no
//! implementations for arrays of a generic length, so a state goes through nested sequences;
//! reading one back checks every length against the mechanism's sizes. Every number, the solve
//! report's too, is written and read as `crate::floats_serde` writes and reads it, so that a
//! NaN or an infinity reads back as it was.

use crate::kin::{DetSigns, Health, Kin};
use crate::solvers::newton::SolveReport;
use serde::{Deserialize, Serialize};

/// The serialized form of [`Kin`]: the same fields as nested sequences. A field it does not
/// have is an error naming it, as in a generated state.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct KinRepr {
    x: Vec<f64>,
    q: Vec<f64>,
    dq: Vec<Vec<f64>>,
    d2q: Vec<Vec<Vec<f64>>>,
    out: Vec<f64>,
    dout: Vec<Vec<f64>>,
    d2out: Vec<Vec<Vec<f64>>>,
    report: SolveReport,
    health: Health,
}

fn to_vec2<const A: usize, const B: usize>(v: &[[f64; B]; A]) -> Vec<Vec<f64>> {
    v.iter().map(|r| r.to_vec()).collect()
}

fn to_vec3<const A: usize, const B: usize, const C: usize>(v: &[[[f64; C]; B]; A]) -> Vec<Vec<Vec<f64>>> {
    v.iter().map(to_vec2).collect()
}

/// `v` as an array of length `N`, or the error naming `field`.
fn array<T, const N: usize>(v: Vec<T>, field: &str) -> Result<[T; N], String> {
    let len = v.len();
    v.try_into().map_err(|_| format!("`{field}` has {len} entries where the mechanism has {N}"))
}

/// `v` as an `A` by `B` array, or the error naming `field`, or the row of it (`dq[1]`), whose
/// length does not fit: the rows of `dq` are as long as the inputs are many, `dq` itself as the
/// unknowns, and naming the field alone told a row's length as if it were the field's.
fn array2<const A: usize, const B: usize>(v: Vec<Vec<f64>>, field: &str) -> Result<[[f64; B]; A], String> {
    let rows: Result<Vec<[f64; B]>, String> =
        v.into_iter().enumerate().map(|(k, r)| array(r, &format!("{field}[{k}]"))).collect();
    array(rows?, field)
}

fn array3<const A: usize, const B: usize, const C: usize>(
    v: Vec<Vec<Vec<f64>>>,
    field: &str,
) -> Result<[[[f64; C]; B]; A], String> {
    let rows: Result<Vec<[[f64; C]; B]>, String> =
        v.into_iter().enumerate().map(|(k, r)| array2(r, &format!("{field}[{k}]"))).collect();
    array(rows?, field)
}

impl<const N: usize, const NI: usize, const NO: usize> From<Kin<N, NI, NO>> for KinRepr {
    fn from(k: Kin<N, NI, NO>) -> Self {
        KinRepr {
            x: k.x.to_vec(),
            q: k.q.to_vec(),
            dq: to_vec2(&k.dq),
            d2q: to_vec3(&k.d2q),
            out: k.out.to_vec(),
            dout: to_vec2(&k.dout),
            d2out: to_vec3(&k.d2out),
            report: k.report,
            health: k.health,
        }
    }
}

impl<const N: usize, const NI: usize, const NO: usize> TryFrom<KinRepr> for Kin<N, NI, NO> {
    type Error = String;
    fn try_from(r: KinRepr) -> Result<Self, String> {
        Ok(Kin {
            x: array(r.x, "x")?,
            q: array(r.q, "q")?,
            dq: array2(r.dq, "dq")?,
            d2q: array3(r.d2q, "d2q")?,
            out: array(r.out, "out")?,
            dout: array2(r.dout, "dout")?,
            d2out: array3(r.d2out, "d2out")?,
            report: r.report,
            health: r.health,
        })
    }
}

impl<const N: usize, const NI: usize, const NO: usize> Serialize for Kin<N, NI, NO> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        crate::floats_serde::within::serialize(&KinRepr::from(*self), s)
    }
}

impl<'de, const N: usize, const NI: usize, const NO: usize> Deserialize<'de> for Kin<N, NI, NO> {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let repr: KinRepr = crate::floats_serde::within::deserialize(d)?;
        Kin::try_from(repr).map_err(serde::de::Error::custom)
    }
}

// The determinant signs as their four words.
impl Serialize for DetSigns {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.words().serialize(s)
    }
}

impl<'de> Deserialize<'de> for DetSigns {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        <[u64; 4]>::deserialize(d).map(DetSigns::from_words)
    }
}

/// Reads [`Health::min_pivot`] as every number of the crate is read (`crate::floats_serde`:
/// a number, `"inf"`, or `null`), with NaN read as the infinity of a state none of whose blocks
/// was factorised: a pivot ratio is never NaN, and JSON written before the infinity was written
/// as `"inf"` holds `null` there.
pub(crate) fn min_pivot<'de, D: serde::Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    let v: f64 = crate::floats_serde::deserialize(d)?;
    Ok(if v.is_nan() { f64::INFINITY } else { v })
}
