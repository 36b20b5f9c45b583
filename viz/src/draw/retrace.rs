//! A traced path without what retraces it: a sweep of many turns passes the same points once a
//! turn, and a path written through every sample would hold the same curve as many times (a
//! thousand turns, a thousand times the segments of one), with nothing more to see.

use std::collections::HashSet;
use std::hash::Hash;

/// Where each point of a path was written: its piece and its place there, `None` where it was
/// left out.
pub(crate) type Written = Vec<Option<(usize, usize)>>;

/// The pieces of the path through `points` (as written: pixels rounded to what the picture
/// resolves, so that points within a fraction of a pixel of each other are equal, at any
/// scale), without its segments drawn before (either way): what only retraces the path is
/// left out, and no segment of it is lost. Consecutive equal points are merged. A path that
/// never passes a segment twice is one piece of all its points.
///
/// Also, per point of `points`, the piece it was written into and its place there (`None`
/// where it was left out or merged into the one before).
pub(crate) fn unretraced<P: Copy + Eq + Hash>(points: impl IntoIterator<Item = P>) -> (Vec<Vec<P>>, Written) {
    let mut drawn = HashSet::new();
    let mut pieces: Vec<Vec<P>> = Vec::new();
    let mut at = Vec::new();
    // Whether the last piece ends at the last point met, and that point.
    let (mut open, mut prev) = (false, None::<P>);
    for p in points {
        if prev == Some(p) {
            at.push(None);
            continue;
        }
        let new = match prev {
            None => true,
            Some(q) => !drawn.contains(&(p, q)) && drawn.insert((q, p)),
        };
        if new {
            if !open {
                // Going on from where the last piece ended keeps it one line; else a new
                // piece from the point before (none at the start).
                let ends_last = prev.is_some() && pieces.last().and_then(|piece| piece.last()).copied() == prev;
                if !ends_last {
                    pieces.push(prev.into_iter().collect());
                }
                open = true;
            }
            let piece = pieces.len() - 1;
            pieces[piece].push(p);
            at.push(Some((piece, pieces[piece].len() - 1)));
        } else {
            open = false;
            at.push(None);
        }
        prev = Some(p);
    }
    (pieces, at)
}

#[cfg(test)]
mod tests {
    use super::unretraced;

    #[test]
    fn a_path_passing_its_points_again_keeps_one_pass() {
        // Once around a square, around again but for the last side, then off to a new point.
        let square = [(0, 0), (1, 0), (1, 1), (0, 1)];
        let path: Vec<(i32, i32)> = square.iter().chain(&square).copied().chain([(5, 5), (5, 5)]).collect();
        let (pieces, at) = unretraced(path);
        // The first turn, closed on its start; then the new stretch from the last point met.
        assert_eq!(pieces, vec![vec![(0, 0), (1, 0), (1, 1), (0, 1), (0, 0)], vec![(0, 1), (5, 5)]]);
        assert_eq!(at[4], Some((0, 4)));
        assert_eq!(at[5..8], [None, None, None]);
        assert_eq!((at[8], at[9]), (Some((1, 1)), None));
        // Back and forth on a segment: drawn once, then on from where the path is.
        let (pieces, _) = unretraced([(0, 0), (1, 0), (0, 0), (1, 0), (0, 0), (2, 2)]);
        assert_eq!(pieces, vec![vec![(0, 0), (1, 0)], vec![(0, 0), (2, 2)]]);
        // A segment between two points met before, not drawn before, is drawn.
        let chord = [(0, 0), (1, 0), (2, 0), (2, 1), (0, 0), (2, 0)];
        assert_eq!(unretraced(chord).0, vec![chord.to_vec()]);
        // A figure eight through its crossing point, once: one piece of every point.
        let eight = [(0, 0), (1, 1), (2, 0), (1, -1), (0, 0), (-1, 1), (-2, 0), (-1, -1), (0, 0)];
        let (pieces, _) = unretraced(eight);
        assert_eq!(pieces, vec![eight.to_vec()]);
        let (pieces, at) = unretraced(Vec::<i32>::new());
        assert!(pieces.is_empty() && at.is_empty());
    }
}
