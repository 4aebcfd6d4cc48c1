//! The small text markup of plot labels: `^{…}` superscript, `_{…}` subscript, and `^`
//! followed by a number (`s^2`, `10^-3`). Parsed in one pass, linear in the length of the text.

/// One run of rich text: normal, superscript or subscript.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Run {
    pub text: String,
    /// 0 normal, 1 superscript, −1 subscript.
    pub level: i8,
}

/// Splits `s` into runs: `^{…}` and `_{…}` are super- and subscripts, and `^` followed by a
/// number (`s^2`, `10^-3`) is a superscript too. Everything else is literal (a `^{` without a
/// closing brace too). Minus signs in scripts become typographic minus signs.
pub(crate) fn rich_runs(s: &str) -> Vec<Run> {
    let mut runs: Vec<Run> = Vec::new();
    let mut cur = String::new();
    let chars: Vec<char> = s.chars().collect();
    // next_close[i]: index of the first '}' at or after i (chars.len() if none), so that each
    // "^{" finds its closing brace in constant time (a scan per "^{" is quadratic on text
    // full of unclosed braces).
    let mut next_close = vec![chars.len(); chars.len() + 1];
    for i in (0..chars.len()).rev() {
        next_close[i] = if chars[i] == '}' {
            i
        } else {
            next_close[i + 1]
        };
    }
    let mut i = 0;
    let push = |runs: &mut Vec<Run>, text: String, level: i8| {
        if !text.is_empty() {
            runs.push(Run { text, level });
        }
    };
    while i < chars.len() {
        let c = chars[i];
        if (c == '^' || c == '_') && i + 1 < chars.len() {
            let level = if c == '^' { 1 } else { -1 };
            if chars[i + 1] == '{' {
                let close = next_close.get(i + 2).copied().unwrap_or(chars.len());
                if close < chars.len() {
                    push(&mut runs, std::mem::take(&mut cur), 0);
                    let inner: String = chars[i + 2..close].iter().collect();
                    push(&mut runs, inner.replace('-', "−"), level);
                    i = close + 1;
                    continue;
                }
            } else if c == '^' {
                let mut j = i + 1;
                if j < chars.len() && (chars[j] == '-' || chars[j] == '−') {
                    j += 1;
                }
                let start_digits = j;
                while j < chars.len() && (chars[j].is_ascii_digit() || chars[j] == '.') {
                    j += 1;
                }
                if j > start_digits {
                    push(&mut runs, std::mem::take(&mut cur), 0);
                    let inner: String = chars[i + 1..j].iter().collect();
                    push(&mut runs, inner.replace('-', "−"), 1);
                    i = j;
                    continue;
                }
            }
        }
        cur.push(c);
        i += 1;
    }
    push(&mut runs, cur, 0);
    runs
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pairs(s: &str) -> Vec<(String, i8)> {
        rich_runs(s)
            .into_iter()
            .map(|r| (r.text, r.level))
            .collect()
    }

    #[test]
    fn rich_text_runs() {
        let r = pairs("10^{-3} s^2 + x_{1}");
        let expect = [
            ("10", 0),
            ("−3", 1),
            (" s", 0),
            ("2", 1),
            (" + x", 0),
            ("1", -1),
        ];
        assert_eq!(r, expect.map(|(t, l)| (t.to_string(), l)));
        // A lone caret or underscore stays literal.
        assert_eq!(pairs("a_b ^ c"), [("a_b ^ c".to_string(), 0)]);
    }

    #[test]
    fn unclosed_braces_stay_literal_and_parse_in_one_pass() {
        assert_eq!(pairs("x^{2"), [("x^{2".to_string(), 0)]);
        // The closing brace of a later group is found, not that of an earlier one.
        assert_eq!(
            pairs("a^{1}b_{2}"),
            [
                ("a".to_string(), 0),
                ("1".to_string(), 1),
                ("b".to_string(), 0),
                ("2".to_string(), -1)
            ]
        );
        // 10 000 unclosed groups: one literal run (quadratic before: a scan per "^{").
        let s = "^{".repeat(10_000);
        assert_eq!(pairs(&s), [(s.clone(), 0)]);
        // Empty groups vanish (and end the run before them).
        assert_eq!(pairs("a^{}b"), [("a".to_string(), 0), ("b".to_string(), 0)]);
    }
}
