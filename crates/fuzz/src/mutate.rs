//! Mutations of a seed file, drawn with `arbitrary` from random bytes: byte-level edits, and
//! edits that know text formats (a number swapped for an extreme one, a line repeated, a token
//! that breaks paths or quoting inserted).

use arbitrary::{Arbitrary, Unstructured};

/// Tokens that break parsers: extreme and non-finite numbers, huge counts, separators, path
/// escapes, broken UTF-8.
const TOKENS: &[&[u8]] = &[
    b"nan",
    b"NaN",
    b"inf",
    b"-inf",
    b"1e309",
    b"-1e309",
    b"1e-320",
    b"1e300",
    b"-1",
    b"0",
    b"-0",
    b"4294967295",
    b"4294967296",
    b"2147483648",
    b"18446744073709551615",
    b"18446744073709551616",
    b"1000000000",
    b"9999999999999999999999",
    b"0.5",
    b"..",
    b"../../../escape",
    b"/tmp/escape",
    b"\n",
    b"\r\n",
    b" ",
    b"\t",
    b",",
    b":",
    b"@",
    b"#",
    b"\"",
    b"'",
    b"[",
    b"]",
    b"{",
    b"}",
    b"=",
    b"%ff",
    b"\xff\xfe",
    b"\xef\xbb\xbf",
    b"\0",
];

#[derive(Arbitrary, Debug)]
enum Mutation {
    FlipBit {
        at: usize,
        bit: u8,
    },
    SetByte {
        at: usize,
        value: u8,
    },
    Insert {
        at: usize,
        bytes: Vec<u8>,
    },
    Delete {
        at: usize,
        len: u8,
    },
    InsertToken {
        at: usize,
        token: usize,
    },
    /// The n-th number of the input becomes a token.
    ReplaceNumber {
        nth: usize,
        token: usize,
    },
    /// The n-th line is repeated `times` times.
    RepeatLine {
        nth: usize,
        times: u8,
    },
    DeleteLine {
        nth: usize,
    },
    /// A slice of another seed put in.
    Splice {
        at: usize,
        seed: usize,
        from: usize,
        len: u16,
    },
    Truncate {
        at: usize,
    },
}

/// Largest input the mutations grow to.
const MAX_LEN: usize = 256 * 1024;

/// `seed` after one to eight mutations drawn from `entropy`; `others` feed splices.
pub fn mutate(seed: &[u8], others: &[Vec<u8>], entropy: &[u8]) -> Vec<u8> {
    let mut u = Unstructured::new(entropy);
    let mut data = seed.to_vec();
    let count = u.int_in_range(1..=8).unwrap_or(1);
    for _ in 0..count {
        let Ok(mutation) = Mutation::arbitrary(&mut u) else {
            break;
        };
        apply(&mut data, mutation, others);
        data.truncate(MAX_LEN);
    }
    data
}

fn apply(data: &mut Vec<u8>, mutation: Mutation, others: &[Vec<u8>]) {
    let at = |i: usize, len: usize| if len == 0 { 0 } else { i % (len + 1) };
    let token = |i: usize| TOKENS[i % TOKENS.len()];
    match mutation {
        Mutation::FlipBit { at: i, bit } if !data.is_empty() => {
            let i = i % data.len();
            data[i] ^= 1 << (bit % 8);
        }
        Mutation::SetByte { at: i, value } if !data.is_empty() => {
            let i = i % data.len();
            data[i] = value;
        }
        Mutation::Insert { at: i, bytes } => {
            let i = at(i, data.len());
            data.splice(i..i, bytes.into_iter().take(64));
        }
        Mutation::Delete { at: i, len } => {
            let i = at(i, data.len());
            let end = (i + len as usize).min(data.len());
            data.drain(i..end);
        }
        Mutation::InsertToken { at: i, token: t } => {
            let i = at(i, data.len());
            data.splice(i..i, token(t).iter().copied());
        }
        Mutation::ReplaceNumber { nth, token: t } => {
            let numbers = number_spans(data);
            if !numbers.is_empty() {
                let (start, end) = numbers[nth % numbers.len()];
                data.splice(start..end, token(t).iter().copied());
            }
        }
        Mutation::RepeatLine { nth, times } => {
            let lines = line_spans(data);
            if !lines.is_empty() {
                let (start, end) = lines[nth % lines.len()];
                let line = data[start..end].to_vec();
                let copies = line.repeat(times as usize % 64);
                data.splice(end..end, copies);
            }
        }
        Mutation::DeleteLine { nth } => {
            let lines = line_spans(data);
            if !lines.is_empty() {
                let (start, end) = lines[nth % lines.len()];
                data.drain(start..end);
            }
        }
        Mutation::Splice {
            at: i,
            seed,
            from,
            len,
        } if !others.is_empty() => {
            let other = &others[seed % others.len()];
            let from = at(from, other.len()).min(other.len());
            let end = (from + len as usize).min(other.len());
            let i = at(i, data.len());
            data.splice(i..i, other[from..end].iter().copied());
        }
        Mutation::Truncate { at: i } => {
            let i = at(i, data.len());
            data.truncate(i);
        }
        _ => {}
    }
}

/// Byte ranges of the runs of digits (with sign, point and exponent) in `data`.
fn number_spans(data: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < data.len() {
        if data[i].is_ascii_digit() {
            let mut start = i;
            if start > 0 && data[start - 1] == b'-' {
                start -= 1;
            }
            while i < data.len() && (data[i].is_ascii_alphanumeric() || b".+-".contains(&data[i])) {
                i += 1;
            }
            spans.push((start, i));
        } else {
            i += 1;
        }
    }
    spans
}

/// Byte ranges of the lines of `data`, each with its newline.
fn line_spans(data: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut start = 0;
    for (i, &b) in data.iter().enumerate() {
        if b == b'\n' {
            spans.push((start, i + 1));
            start = i + 1;
        }
    }
    if start < data.len() {
        spans.push((start, data.len()));
    }
    spans
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_number_can_become_a_huge_count() {
        let seed = b"element vertex 3\n";
        let mutated = {
            let mut data = seed.to_vec();
            apply(
                &mut data,
                Mutation::ReplaceNumber { nth: 0, token: 16 },
                &[],
            );
            data
        };
        assert_eq!(mutated, b"element vertex 1000000000\n");
    }

    #[test]
    fn lines_repeat_and_vanish_whole() {
        let mut data = b"a\nb\nc".to_vec();
        apply(&mut data, Mutation::RepeatLine { nth: 1, times: 2 }, &[]);
        assert_eq!(data, b"a\nb\nb\nb\nc");
        apply(&mut data, Mutation::DeleteLine { nth: 0 }, &[]);
        assert_eq!(data, b"b\nb\nb\nc");
    }

    #[test]
    fn mutations_stay_within_bounds_of_any_input() {
        for len in 0..4 {
            let seed = vec![b'7'; len];
            for k in 0u8..200 {
                let entropy: Vec<u8> = (0..64)
                    .map(|i| k.wrapping_mul(31).wrapping_add(i))
                    .collect();
                assert!(mutate(&seed, &[b"1 2".to_vec()], &entropy).len() <= MAX_LEN);
            }
        }
    }
}
