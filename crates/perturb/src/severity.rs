//! How strong a frame corruption is: a whole severity 0..=5 (the catalogue's tables) or a real
//! one in [0, 5] in steps of 0.01, whose parameters are interpolated between the tables' rows.

use std::fmt;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A severity in [0, 5], held in hundredths so that it compares, hashes and prints exactly.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Severity(u16);

impl Severity {
    /// The clean frame: an item at severity 0 leaves frames as they are.
    pub const CLEAN: Severity = Severity(0);
    pub const MAX: Severity = Severity(500);

    /// A whole severity; `None` above 5.
    pub const fn whole(severity: u8) -> Option<Self> {
        if severity <= 5 {
            Some(Severity(severity as u16 * 100))
        } else {
            None
        }
    }

    /// `hundredths / 100`; `None` above 5.
    pub const fn from_hundredths(hundredths: u16) -> Option<Self> {
        if hundredths <= 500 {
            Some(Severity(hundredths))
        } else {
            None
        }
    }

    /// A number in [0, 5] with at most two decimals; `None` for anything else.
    pub fn from_value(value: f64) -> Option<Self> {
        let hundredths = value * 100.0;
        let rounded = hundredths.round();
        let on_grid = (hundredths - rounded).abs() < 1e-6;
        (value.is_finite() && on_grid && (0.0..=500.0).contains(&rounded))
            .then_some(Severity(rounded as u16))
    }

    /// `0`…`5`, `low`/`mid`/`high` (1, 3, 5), or a real number in [0, 5] with at most two
    /// decimals (`2.5`, `0.75`).
    pub fn parse(text: &str) -> Option<Self> {
        match text {
            "low" => Self::whole(1),
            "mid" => Self::whole(3),
            "high" => Self::whole(5),
            _ if text.starts_with(['-', '+']) => None,
            _ => Self::from_value(text.parse::<f64>().ok()?),
        }
    }

    pub fn hundredths(self) -> u16 {
        self.0
    }

    pub fn value(self) -> f64 {
        self.0 as f64 / 100.0
    }

    /// The whole severity it is, if it is one.
    pub fn as_whole(self) -> Option<u8> {
        self.0.is_multiple_of(100).then_some((self.0 / 100) as u8)
    }

    pub fn is_clean(self) -> bool {
        self.0 == 0
    }

    /// The whole severity at or below it (a 5-entry table's row is `floor() - 1`).
    pub fn floor(self) -> u8 {
        (self.0 / 100) as u8
    }

    /// The whole severity at or above it.
    pub fn ceil(self) -> u8 {
        self.0.div_ceil(100) as u8
    }

    /// A parameter at this severity from its value on the clean frame and its table at 1..=5,
    /// linear between neighbouring rows. Whole severities return the table's value itself, so
    /// they keep the bytes they always had.
    pub fn interpolate(self, clean: f64, table: &[f64; 5]) -> f64 {
        let row = |s: u8| if s == 0 { clean } else { table[s as usize - 1] };
        match self.as_whole() {
            Some(s) => row(s),
            None => {
                let (low, high) = (row(self.floor()), row(self.ceil()));
                let t = (self.0 % 100) as f64 / 100.0;
                low + t * (high - low)
            }
        }
    }

    /// As [`Severity::interpolate`], but linear in `measure(parameter)` (e.g. 1/photons, which
    /// grows with the noise where photons do not); `clean_measure` is the measure at 0 and
    /// `inverse` turns a measure back into the parameter. Whole severities return the table.
    pub fn interpolate_in(
        self,
        clean_measure: f64,
        table: &[f64; 5],
        measure: fn(f64) -> f64,
        inverse: fn(f64) -> f64,
    ) -> f64 {
        match self.as_whole() {
            Some(s) if s > 0 => table[s as usize - 1],
            _ => inverse(self.interpolate(clean_measure, &table.map(measure))),
        }
    }
}

impl fmt::Display for Severity {
    /// `3`, `2.5`, `0.05`: the shortest text [`Severity::parse`] reads back.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (whole, part) = (self.0 / 100, self.0 % 100);
        match (part, part % 10) {
            (0, _) => write!(f, "{whole}"),
            (_, 0) => write!(f, "{whole}.{}", part / 10),
            _ => write!(f, "{whole}.{part:02}"),
        }
    }
}

/// A whole severity is written as an integer (as it always was), a real one as a number.
impl Serialize for Severity {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self.as_whole() {
            Some(s) => serializer.serialize_u8(s),
            None => serializer.serialize_f64(self.value()),
        }
    }
}

impl<'de> Deserialize<'de> for Severity {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = f64::deserialize(deserializer)?;
        Severity::from_value(value).ok_or_else(|| {
            serde::de::Error::custom(format!(
                "severity {value}: expected a number in [0, 5] with at most two decimals"
            ))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_round_trips_and_whole_severities_print_as_integers() {
        for (text, hundredths) in [
            ("0", 0),
            ("3", 300),
            ("2.5", 250),
            ("0.05", 5),
            ("4.75", 475),
        ] {
            let s = Severity::parse(text).unwrap();
            assert_eq!(s.hundredths(), hundredths, "{text}");
            assert_eq!(s.to_string(), text);
        }
        assert_eq!(Severity::parse("mid"), Severity::whole(3));
        assert_eq!(Severity::parse("2.50"), Severity::from_hundredths(250));
        for bad in ["5.01", "-1", "+2", "2.125", "nan", "inf", "", "two"] {
            assert_eq!(Severity::parse(bad), None, "{bad}");
        }
    }

    #[test]
    fn json_keeps_integers_for_whole_severities() {
        let whole = Severity::whole(3).unwrap();
        let real = Severity::from_hundredths(275).unwrap();
        assert_eq!(serde_json::to_string(&whole).unwrap(), "3");
        assert_eq!(serde_json::to_string(&real).unwrap(), "2.75");
        for s in [whole, real] {
            let json = serde_json::to_string(&s).unwrap();
            assert_eq!(serde_json::from_str::<Severity>(&json).unwrap(), s);
        }
        assert!(serde_json::from_str::<Severity>("5.5").is_err());
    }

    #[test]
    fn interpolation_is_the_table_at_whole_severities_and_linear_between() {
        let table = [0.08, 0.12, 0.18, 0.26, 0.38];
        for s in 1..=5u8 {
            let at = Severity::whole(s).unwrap().interpolate(0.0, &table);
            assert_eq!(at.to_bits(), table[s as usize - 1].to_bits());
        }
        assert_eq!(Severity::CLEAN.interpolate(0.7, &table), 0.7);
        let mid = Severity::parse("2.5").unwrap().interpolate(0.0, &table);
        assert!((mid - 0.15).abs() < 1e-12, "{mid}");
        let low = Severity::parse("0.25").unwrap().interpolate(1.0, &table);
        assert!((low - (1.0 + 0.25 * (0.08 - 1.0))).abs() < 1e-12, "{low}");
    }
}
