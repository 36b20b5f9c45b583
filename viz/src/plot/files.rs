//! Where figures go, writing them, and thinning long curves.

use super::PlotError;
use std::path::{Path, PathBuf};

/// Writes an SVG document to `path`, creating its folder.
pub fn save(path: &Path, svg: &str) -> Result<(), PlotError> {
    let io = |source| PlotError::Io { path: path.to_path_buf(), source };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(io)?;
    }
    std::fs::write(path, svg).map_err(io)
}

fn created(dir: PathBuf) -> Result<PathBuf, PlotError> {
    std::fs::create_dir_all(&dir).map_err(|source| PlotError::Io { path: dir.clone(), source })?;
    Ok(dir)
}

/// Output folder of a program's figures: `$KINLOOP_OUT/<name>` (default `out/<name>`),
/// created if missing.
pub fn out_dir(name: &str) -> Result<PathBuf, PlotError> {
    let base = std::env::var_os("KINLOOP_OUT").map_or_else(|| PathBuf::from("out"), PathBuf::from);
    created(base.join(name))
}

/// Folder for figures meant to be kept (a documentation gallery): `$KINLOOP_FIGURES/<name>`
/// when that variable is set, else [`out_dir`].
pub fn figure_dir(name: &str) -> Result<PathBuf, PlotError> {
    match std::env::var_os("KINLOOP_FIGURES") {
        Some(base) => created(PathBuf::from(base).join(name)),
        None => out_dir(name),
    }
}

/// At most `max` points of a curve, equally strided, keeping the first and the last (for
/// smaller files; the charts already skip points closer than half a pixel). A curve keeps its
/// ends: a `max` below 2 counts as 2. A gap (a non-finite point: a sample that failed) is
/// never bridged: where the points skipped between two kept finite ones hold one, the first
/// such is kept too, and the stride is widened until the points kept, gaps with them, are at
/// most `max` (at most 3 where `max` is 2: the ends and a gap between them).
///
/// ```
/// use kinloop_viz::plot::decimate;
/// let pts: Vec<(f64, f64)> = (0..=100).map(|i| (i as f64, 0.0)).collect();
/// let d = decimate(&pts, 11);
/// assert_eq!(d.len(), 11);
/// assert_eq!((d[0], d[10]), (pts[0], pts[100]));
/// assert_eq!(decimate(&pts, 0), [pts[0], pts[100]]);
/// // A failed sample between two kept points stays a gap in the curve.
/// let mut gap = pts.clone();
/// gap[55] = (55.0, f64::NAN);
/// let d = decimate(&gap, 11);
/// assert!(d.len() <= 11 && d.iter().any(|p| p.1.is_nan()));
/// ```
pub fn decimate(points: &[(f64, f64)], max: usize) -> Vec<(f64, f64)> {
    // Every point was kept for a `max` of 0 or 1, against "at most `max`".
    let max = max.max(2);
    if points.len() <= max {
        return points.to_vec();
    }
    let last = points.len() - 1;
    let mut stride = last.div_ceil(max - 1);
    loop {
        let out = strided(points, stride);
        // The widest stride keeps the two ends and at most one gap between them.
        if out.len() <= max || stride >= last {
            return out;
        }
        // Each gap kept takes the place of a strided point: wider steps, about an eighth at a
        // time, until they fit.
        stride += stride.div_ceil(8);
    }
}

/// Every `stride`-th point and the last, with the first non-finite point skipped between two
/// kept finite ones (a gap the curve must keep).
fn strided(points: &[(f64, f64)], stride: usize) -> Vec<(f64, f64)> {
    let finite = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
    let last = points.len() - 1;
    // By index, not by value: a last point that is not finite (a sweep that stopped) never
    // equals itself, and would be written twice, one point over `max`.
    let mut kept: Vec<usize> = (0..=last).step_by(stride).collect();
    if !last.is_multiple_of(stride) {
        kept.push(last);
    }
    let mut out = Vec::with_capacity(kept.len() + 1);
    for (k, &i) in kept.iter().enumerate() {
        if k > 0 {
            let before = kept[k - 1];
            if finite(&points[before]) && finite(&points[i]) {
                out.extend(points[before + 1..i].iter().find(|p| !finite(p)));
            }
        }
        out.push(points[i]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::decimate;

    #[test]
    fn a_curve_ending_in_a_gap_keeps_at_most_max_points() {
        // A sweep that stopped: its last point is not finite, and equals no point, not even
        // itself.
        let mut pts: Vec<(f64, f64)> = (0..9).map(|i| (i as f64, 1.0)).collect();
        pts.push((f64::NAN, f64::NAN));
        let d = decimate(&pts, 4);
        assert_eq!(d.len(), 4, "{d:?}");
        assert_eq!(d[..3], [(0.0, 1.0), (3.0, 1.0), (6.0, 1.0)]);
        assert!(d[3].0.is_nan() && d[3].1.is_nan());
        // Also where the stride does not reach the last point.
        pts.push((f64::NAN, 0.0));
        let d = decimate(&pts, 4);
        assert_eq!(d.len(), 4, "{d:?}");
        assert!(d[3].0.is_nan());
    }

    /// A failed sample among those skipped stays a gap: the curve was drawn straight across it,
    /// as if the sweep had solved there. Every pair of consecutive kept points that are finite
    /// has no non-finite point of the curve between them, and at most `max` points are kept.
    #[test]
    fn a_gap_between_kept_points_is_kept() {
        let nan = f64::NAN;
        let curve = |gaps: &[usize], n: usize| -> Vec<(f64, f64)> {
            (0..n).map(|i| (i as f64, if gaps.contains(&i) { nan } else { (i as f64).sin() })).collect()
        };
        for (gaps, n, max) in [
            (&[55][..], 101, 11),
            (&[3, 4, 5], 101, 11),
            (&[1, 13, 27, 41, 58, 77, 93], 101, 6),
            (&[50], 101, 2),
            (&[50], 101, 3),
            (&[10, 11, 12, 700, 701, 9000], 10_000, 500),
        ] {
            let pts = curve(gaps, n);
            let d = decimate(&pts, max);
            assert!(d.len() <= max.max(3), "{gaps:?} {max}: {} points", d.len());
            assert_eq!((d[0].0, d[d.len() - 1].0), (0.0, (n - 1) as f64), "{gaps:?} {max}: the ends");
            for w in d.windows(2) {
                let ([a, b], finite) = ([w[0].0, w[1].0], w[0].1.is_finite() && w[1].1.is_finite());
                let bridged = gaps.iter().any(|&g| a < g as f64 && (g as f64) < b);
                assert!(!(finite && bridged), "{gaps:?} {max}: {a} to {b} bridges a gap");
            }
        }
    }
}
