//! Did-you-mean suggestions for misspelt names.

/// Suggests a candidate close to a misspelt name, or one that differs in case alone. Close is
/// at most 2 edits (a swap of neighbours counting as one), or a third of the name's length for
/// a long name (`sensitivity` is 3 edits from `sensitivities`), or a candidate the name begins
/// when it has 4 letters or more and at least half the candidate's (`sensitiv`). A short name
/// is never close to a long candidate it is only the start of. The nearest ignoring case
/// comes first, so that `Sin` is `sin` and not `min` (both one edit away) and `PI` is `pi`;
/// then the nearest as written; ties are broken by name so the message is deterministic. A name
/// written with Greek letters, as a formula from a paper writes it (`φ`, `θ2`), is the candidate
/// that spells them out (`phi`, `theta2`) before any other, and a name that spells out a
/// candidate's Greek letters is that candidate (`phi` is a declared `φ`).
pub fn similar<'a>(name: &str, candidates: impl Iterator<Item = &'a String>) -> Option<&'a String> {
    // The distance is quadratic in the lengths: long names get no suggestion.
    const LONGEST: usize = 64;
    if name.chars().count() > LONGEST {
        return None;
    }
    let spelled = spelled_out(name);
    let lower = name.to_lowercase();
    let candidates: Vec<&String> = candidates.collect();
    if let Some(spelled) = spelled
        && let Some(c) = candidates.iter().find(|c| ***c == spelled)
    {
        return Some(c);
    }
    // The other way round: the name spelt out where a candidate is written in Greek (`phi` for
    // a declared `φ`), which edits would take for another Latin name (`psi`, one edit away).
    if let Some(c) = candidates.iter().find(|c| spelled_out(c).is_some_and(|s| s == name)) {
        return Some(c);
    }
    candidates
        .into_iter()
        .filter(|c| c.chars().count() <= LONGEST)
        .map(|c| (edit_distance(name, c), edit_distance(&lower, &c.to_lowercase()), c))
        .filter(|(d, folded, c)| *folded == 0 || close(&lower, &c.to_lowercase(), *folded.min(d)))
        .min_by(|a, b| a.1.cmp(&b.1).then_with(|| a.0.cmp(&b.0)).then_with(|| a.2.cmp(b.2)))
        .map(|(_, _, c)| c)
}

/// `name` with each Greek letter spelt out in the Latin letters a name of the language uses
/// (`φ2` is `phi2`, `Δx` is `deltax`), or `None` where it has no Greek letter.
fn spelled_out(name: &str) -> Option<String> {
    const LETTERS: [&str; 25] = [
        "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa", "lambda", "mu", "nu",
        "xi", "omicron", "pi", "rho", "sigma", "sigma", "tau", "upsilon", "phi", "chi", "psi", "omega",
    ];
    let mut greek = false;
    let spelled = name
        .chars()
        .flat_map(|c| {
            // Lower case from U+03B1 (alpha) to U+03C9 (omega), U+03C2 the final sigma; capitals
            // 0x20 below them; the symbol forms of phi and theta.
            let index = match c {
                '\u{03b1}'..='\u{03c9}' => Some(c as u32 - 0x03b1),
                '\u{0391}'..='\u{03a9}' if c != '\u{03a2}' => Some(c as u32 - 0x0391),
                '\u{03d5}' => Some(0x03c6 - 0x03b1),
                '\u{03d1}' => Some(0x03b8 - 0x03b1),
                _ => None,
            };
            greek |= index.is_some();
            match index {
                Some(i) => LETTERS[i as usize].chars().collect::<Vec<_>>(),
                None => vec![c],
            }
        })
        .collect();
    greek.then_some(spelled)
}

/// Whether `candidate`, `distance` edits from `name` (both in lower case), is close enough to
/// suggest (see [`similar`]).
fn close(name: &str, candidate: &str, distance: usize) -> bool {
    let (n, c) = (name.chars().count(), candidate.chars().count());
    // A one-letter name is not "close" to another one-letter name: every edit is the word.
    let near = distance <= (n / 3).max(2) && distance < n.max(c);
    let start = n >= 4 && 2 * n >= c && candidate.starts_with(name);
    near || start
}

/// Optimal string alignment distance (Levenshtein plus adjacent transpositions).
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut v = (d[i - 1][j] + 1).min(d[i][j - 1] + 1).min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                v = v.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = v;
        }
    }
    d[a.len()][b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances_by_hand() {
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("ab", "ba"), 1, "a swap of neighbours is one edit");
        assert_eq!(edit_distance("psi", "psi"), 0);
        // y -> i, then e and s added.
        assert_eq!(edit_distance("sensitivity", "sensitivities"), 3);
    }

    #[test]
    fn suggestions_are_close_and_deterministic() {
        let names: Vec<String> = ["beta", "gamma", "delta", "sin", "sign"].iter().map(|s| s.to_string()).collect();
        assert_eq!(similar("gamam", names.iter()).map(String::as_str), Some("gamma"));
        assert_eq!(similar("zzzzzz", names.iter()), None);
        // `sinn` is one edit from `sin` and from `sign`: the tie goes to the first by name.
        assert_eq!(similar("sinn", names.iter()).map(String::as_str), Some("sign"));
        // A difference of case is closer than a different letter: `Sin` is `sin`, not `min`.
        let functions: Vec<String> = ["min", "sin"].iter().map(|s| s.to_string()).collect();
        assert_eq!(similar("Sin", functions.iter()).map(String::as_str), Some("sin"));
        // A long name is close at more edits, and a name the start of a candidate is close:
        // `sensitivity` (3 edits, 11 letters) and `sensitiv` are `sensitivities`; short words
        // are not, at 3 edits or as the start of a long word.
        let options: Vec<String> = ["dense", "newton", "sensitivities"].iter().map(|s| s.to_string()).collect();
        for long in ["sensitivity", "sensitiv", "Sensitivity"] {
            assert_eq!(similar(long, options.iter()).map(String::as_str), Some("sensitivities"), "{long}");
        }
        for short in ["sen", "new", "ds", "fast", "sent", "newtonian_solver"] {
            assert_eq!(similar(short, options.iter()), None, "{short}");
        }
        // A Greek letter is the name that spells it out, before any other.
        let angles: Vec<String> = ["phi", "psi", "theta2", "deltax", "pi"].iter().map(|s| s.to_string()).collect();
        for (greek, latin) in
            [("φ", "phi"), ("ϕ", "phi"), ("ψ", "psi"), ("Ψ", "psi"), ("θ2", "theta2"), ("Δx", "deltax")]
        {
            assert_eq!(similar(greek, angles.iter()).map(String::as_str), Some(latin), "{greek}");
        }
        assert_eq!(similar("ω", angles.iter()), None, "no `omega` among the names");
        // A name spelt out is the candidate written in Greek, before a Latin name an edit away.
        let greek: Vec<String> = ["psi", "φ", "θ2", "theta"].iter().map(|s| s.to_string()).collect();
        for (latin, written) in [("phi", "φ"), ("theta2", "θ2")] {
            assert_eq!(similar(latin, greek.iter()).map(String::as_str), Some(written), "{latin}");
        }
        assert_eq!(similar("theta", greek.iter()).map(String::as_str), Some("theta"), "the name itself");
        assert_eq!(spelled_out("phi"), None);
        assert_eq!(spelled_out("ςσΣ").as_deref(), Some("sigmasigmasigma"));
        // A one-letter name is never "close" to another one-letter name.
        let short: Vec<String> = vec!["a".into()];
        assert_eq!(similar("b", short.iter()), None);
    }
}
