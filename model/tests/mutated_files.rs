//! The shipped declaration files (`cli/mechanisms/*.kl`, what `kinloop` reads), mutated a
//! character at a time, are read without a panic, and when accepted are checked, solved, swept
//! and drawn without one. The mutations are those of a text edited by hand: characters deleted,
//! inserted or doubled (comment markers, brackets, quotes, letters outside ASCII), numbers
//! replaced by extreme ones, names exchanged, lines swapped. Deterministic (a fixed seed); time
//! is bounded by the number of cases, never measured. `KINLOOP_FUZZ_CASES` runs more per file.

use kinloop_model::{Model, ReadError, source};

/// The shipped files, by name.
const FILES: &[(&str, &str)] = &[
    ("coupler_four_bar.kl", include_str!("../../cli/mechanisms/coupler_four_bar.kl")),
    ("dwell_cam.kl", include_str!("../../cli/mechanisms/dwell_cam.kl")),
    ("engine.kl", include_str!("../../cli/mechanisms/engine.kl")),
    ("five_bar.kl", include_str!("../../cli/mechanisms/five_bar.kl")),
    ("four_bar.kl", include_str!("../../cli/mechanisms/four_bar.kl")),
    ("rhombic_drive.kl", include_str!("../../cli/mechanisms/rhombic_drive.kl")),
    ("slider_crank.kl", include_str!("../../cli/mechanisms/slider_crank.kl")),
];

/// Characters inserted: the language's punctuation, the starts of comments and literals, and
/// letters and marks outside ASCII (wide, combining, a byte-order mark, a right-to-left mark).
const CHARS: &[char] = &[
    '(', ')', '[', ']', '{', '}', ',', ';', ':', '=', '@', '+', '-', '*', '/', '^', '.', '#', '!', '"', '\'', '\\',
    '\n', '\t', ' ', '0', '9', 'e', 'x', '_', 'é', 'λ', '°', '😀', '\u{301}', '\u{feff}', '\u{200f}', '\0',
];

/// Numbers put in place of one of the text's.
const NUMBERS: &[&str] = &["0", "-0", "1e308", "-1e308", "1e-320", "4.9e-324", "1e309", "0.0.0", "1e", "00", "1_000"];

/// A small deterministic generator (SplitMix64).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// A number in `0..n` (`n > 0`).
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// The byte offsets of the starts of `text`'s characters, and its end.
fn boundaries(text: &str) -> Vec<usize> {
    text.char_indices().map(|(i, _)| i).chain([text.len()]).collect()
}

/// The spans of the runs of characters of `text` that `keep` accepts.
fn runs(text: &str, keep: impl Fn(char) -> bool) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in text.char_indices().chain([(text.len(), ' ')]) {
        match (start, keep(c) && i < text.len()) {
            (None, true) => start = Some(i),
            (Some(s), false) => {
                out.push((s, i));
                start = None;
            }
            _ => {}
        }
    }
    out
}

/// `text` with one edit.
fn mutate(text: &str, rng: &mut Rng) -> String {
    let cuts = boundaries(text);
    let at = cuts[rng.below(cuts.len())];
    let mut t = text.to_string();
    match rng.below(7) {
        // Delete up to 8 characters.
        0 => {
            let end = cuts[(cuts.iter().position(|&c| c == at).unwrap() + 1 + rng.below(8)).min(cuts.len() - 1)];
            t.replace_range(at..end, "");
        }
        // Insert a character.
        1 => t.insert(at, CHARS[rng.below(CHARS.len())]),
        // Double a stretch of up to 40 characters.
        2 => {
            let end = cuts[(cuts.iter().position(|&c| c == at).unwrap() + rng.below(40)).min(cuts.len() - 1)];
            let piece = t[at..end].to_string();
            t.insert_str(at, &piece);
        }
        // A number replaced by an extreme one, or one that is no number.
        3 => {
            let numbers = runs(text, |c| c.is_ascii_digit() || c == '.');
            if let Some(&(s, e)) = numbers.get(rng.below(numbers.len().max(1))) {
                t.replace_range(s..e, NUMBERS[rng.below(NUMBERS.len())]);
            }
        }
        // A name replaced by another of the text's.
        4 => {
            let names = runs(text, |c| c.is_alphanumeric() || c == '_');
            if !names.is_empty() {
                let (s, e) = names[rng.below(names.len())];
                let (s2, e2) = names[rng.below(names.len())];
                t.replace_range(s..e, &text[s2..e2]);
            }
        }
        // Two lines exchanged.
        5 => {
            let mut lines: Vec<&str> = text.lines().collect();
            // An earlier edit may have cut the text to nothing.
            if !lines.is_empty() {
                let (a, b) = (rng.below(lines.len()), rng.below(lines.len()));
                lines.swap(a, b);
                t = lines.join("\n");
            }
        }
        // The text cut short.
        _ => t.truncate(at),
    }
    t
}

/// Reads `text`; when accepted, checks its report, solves it, sweeps it and draws it (any
/// result but a panic is fine).
fn exercise(name: &str, text: &str) {
    match Model::read(name, text) {
        Ok(mut m) => {
            // Parameters without a default: a value each, as `--params` would give.
            let unset: Vec<String> = (m.params().iter().zip(m.param_values()))
                .filter(|(_, v)| v.is_none())
                .map(|(p, _)| p.clone())
                .collect();
            for p in unset {
                m.set_param(&p, 1.5);
            }
            let _ = (m.decomposition().len(), m.columns(), m.quantities().len());
            if let Some(w) = m.warnings() {
                let _ = w.render(false);
            }
            let ni = m.inputs().len();
            for x in [0.0, 1.0, -2.5] {
                if let Ok(s) = m.solve(&vec![x; ni]) {
                    let _ = s.row();
                }
            }
            let mut guess = vec![0.0; m.unknowns().len()];
            if m.guess(&vec![0.0; ni], &mut guess).is_ok()
                && let Ok(sweep) = m.sweep(&vec![0.0; ni], &vec![1.0; ni], 5, &guess)
            {
                for _ in sweep.take(5) {}
            }
            if let Ok(motion) = m.motion(&vec![0.0; ni], &vec![1.0; ni], 3, &guess) {
                let _ = m.drawing().animate(&motion, &Default::default());
            }
        }
        Err(ReadError::Rejected(d)) => {
            assert!(!d.items.is_empty(), "{name}: rejected without a diagnostic:\n{text}");
            let _ = d.render(false);
        }
        Err(ReadError::Unsupported(_)) => {}
    }
    // Nothing read above is kept: the spans of this text may go.
    source::forget_spans();
}

#[test]
fn mutated_shipped_files_never_panic() {
    let cases: usize = std::env::var("KINLOOP_FUZZ_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(25);
    let mut rng = Rng(0x006b_696e_6c6f_6f70);
    for (name, text) in FILES {
        for case in 0..cases {
            // One to three edits on the same text.
            let mut t = text.to_string();
            for _ in 0..=rng.below(3) {
                t = mutate(&t, &mut rng);
            }
            let run = std::panic::catch_unwind(|| exercise(name, &t));
            assert!(run.is_ok(), "{name}, case {case}: a panic on\n{t}");
        }
    }
}
