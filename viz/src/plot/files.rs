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
/// ends: a `max` below 2 counts as 2.
///
/// ```
/// use kinloop_viz::plot::decimate;
/// let pts: Vec<(f64, f64)> = (0..=100).map(|i| (i as f64, 0.0)).collect();
/// let d = decimate(&pts, 11);
/// assert_eq!(d.len(), 11);
/// assert_eq!((d[0], d[10]), (pts[0], pts[100]));
/// assert_eq!(decimate(&pts, 0), [pts[0], pts[100]]);
/// ```
pub fn decimate(points: &[(f64, f64)], max: usize) -> Vec<(f64, f64)> {
    // Every point was kept for a `max` of 0 or 1, against "at most `max`".
    let max = max.max(2);
    if points.len() <= max {
        return points.to_vec();
    }
    let stride = (points.len() - 1).div_ceil(max - 1);
    let mut out: Vec<(f64, f64)> = points.iter().step_by(stride).copied().collect();
    // By index, not by value: a last point that is not finite (a sweep that stopped) never
    // equals itself, and would be written twice, one point over `max`.
    if !(points.len() - 1).is_multiple_of(stride) {
        out.push(points[points.len() - 1]);
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
}
