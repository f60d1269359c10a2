//! Which sequences a process makes: shard I of N holds the names that hash to I, so membership
//! depends on nothing but the name and N, and stays put when the suite grows.

use std::fmt;

use rslam_core::hash::{fnv1a64, splitmix64};
use rslam_core::printable;

use crate::SuiteError;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

/// Where a shard came from, for the log line of a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShardSource {
    Option,
    Slurm,
    Kubernetes,
    Whole,
}

impl Shard {
    pub const WHOLE: Shard = Shard { index: 0, count: 1 };

    pub fn new(index: usize, count: usize, option: &str) -> Result<Self, SuiteError> {
        if count == 0 || index >= count {
            return Err(SuiteError::option(
                option,
                format!("shard {index} of {count}: expected 0 <= index < count"),
            ));
        }
        Ok(Self { index, count })
    }

    /// `I/N`, e.g. `0/4`.
    pub fn parse(text: &str) -> Result<Self, SuiteError> {
        let bad = || {
            SuiteError::option(
                "--shard",
                format!("'{}': expected I/N, e.g. 0/4", printable(text)),
            )
        };
        let (index, count) = text.split_once('/').ok_or_else(bad)?;
        let index = index.trim().parse().map_err(|_| bad())?;
        let count = count.trim().parse().map_err(|_| bad())?;
        Self::new(index, count, "--shard")
    }

    /// `option` when given; else Slurm's array task (`SLURM_ARRAY_TASK_ID` from
    /// `SLURM_ARRAY_TASK_MIN`, of `SLURM_ARRAY_TASK_COUNT`); else a Kubernetes Indexed Job's
    /// `JOB_COMPLETION_INDEX` of `shard_count`; else the whole suite.
    pub fn resolve(
        option: Option<&str>,
        shard_count: Option<usize>,
        env: impl Fn(&str) -> Option<String>,
    ) -> Result<(Self, ShardSource), SuiteError> {
        if let Some(text) = option {
            return Ok((Self::parse(text)?, ShardSource::Option));
        }
        let number = |name: &str| -> Result<Option<usize>, SuiteError> {
            env(name)
                .map(|v| {
                    v.trim().parse().map_err(|_| {
                        SuiteError::option(name, format!("'{v}': expected a whole number"))
                    })
                })
                .transpose()
        };
        if let Some(id) = number("SLURM_ARRAY_TASK_ID")? {
            let min = number("SLURM_ARRAY_TASK_MIN")?.unwrap_or(0);
            let count = number("SLURM_ARRAY_TASK_COUNT")?.ok_or_else(|| {
                SuiteError::option(
                    "SLURM_ARRAY_TASK_COUNT",
                    "not set beside SLURM_ARRAY_TASK_ID: pass --shard I/N",
                )
            })?;
            let index = id.checked_sub(min).ok_or_else(|| {
                SuiteError::option(
                    "SLURM_ARRAY_TASK_ID",
                    format!("{id} is below SLURM_ARRAY_TASK_MIN {min}"),
                )
            })?;
            return Ok((
                Self::new(index, count, "SLURM_ARRAY_TASK_ID")?,
                ShardSource::Slurm,
            ));
        }
        if let Some(index) = number("JOB_COMPLETION_INDEX")? {
            let count = shard_count.ok_or_else(|| {
                SuiteError::option(
                    "--shard-count",
                    "JOB_COMPLETION_INDEX is set (a Kubernetes Indexed Job): pass --shard-count N, the Job's completions",
                )
            })?;
            return Ok((
                Self::new(index, count, "JOB_COMPLETION_INDEX")?,
                ShardSource::Kubernetes,
            ));
        }
        Ok((Self::WHOLE, ShardSource::Whole))
    }

    pub fn contains(&self, name: &str) -> bool {
        self.count == 1
            || splitmix64(fnv1a64(name.as_bytes())) % self.count as u64 == self.index as u64
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env_of<'a>(pairs: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |name| {
            pairs
                .iter()
                .find(|(k, _)| *k == name)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn a_shard_with_a_line_break_is_quoted_on_one_line() {
        let err = Shard::parse("0/\n4x").unwrap_err().to_string();
        assert_eq!(err, "--shard: '0/\\n4x': expected I/N, e.g. 0/4");
    }

    #[test]
    fn every_name_is_in_exactly_one_shard() {
        let names: Vec<String> = (0..500)
            .map(|i| format!("room{i}__fog-{}", i % 5))
            .collect();
        for count in [1, 2, 3, 7] {
            let mut sizes = vec![0; count];
            for name in &names {
                let holders: Vec<usize> = (0..count)
                    .filter(|&i| Shard { index: i, count }.contains(name))
                    .collect();
                assert_eq!(holders.len(), 1, "{name} in shards {holders:?} of {count}");
                sizes[holders[0]] += 1;
            }
            let expected = names.len() as f64 / count as f64;
            for size in sizes {
                assert!(
                    (size as f64 - expected).abs() < 4.0 * expected.sqrt() + 1.0,
                    "{size} vs {expected}"
                );
            }
        }
    }

    #[test]
    fn the_option_wins_then_slurm_then_kubernetes() {
        let slurm = [
            ("SLURM_ARRAY_TASK_ID", "3"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
            ("JOB_COMPLETION_INDEX", "1"),
        ];
        let (shard, source) = Shard::resolve(Some("1/2"), None, env_of(&slurm)).unwrap();
        assert_eq!(
            (shard, source),
            (Shard { index: 1, count: 2 }, ShardSource::Option)
        );
        let (shard, source) = Shard::resolve(None, None, env_of(&slurm)).unwrap();
        assert_eq!(
            (shard, source),
            (Shard { index: 3, count: 4 }, ShardSource::Slurm)
        );
        let offset = [
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_MIN", "4"),
            ("SLURM_ARRAY_TASK_COUNT", "2"),
        ];
        assert_eq!(
            Shard::resolve(None, None, env_of(&offset)).unwrap().0,
            Shard { index: 1, count: 2 }
        );
        let k8s = [("JOB_COMPLETION_INDEX", "2")];
        let (shard, source) = Shard::resolve(None, Some(5), env_of(&k8s)).unwrap();
        assert_eq!(
            (shard, source),
            (Shard { index: 2, count: 5 }, ShardSource::Kubernetes)
        );
        assert!(
            Shard::resolve(None, None, env_of(&k8s)).is_err(),
            "an index without a count"
        );
        assert_eq!(
            Shard::resolve(None, None, env_of(&[])).unwrap(),
            (Shard::WHOLE, ShardSource::Whole)
        );
    }

    #[test]
    fn malformed_shards_are_refused() {
        for bad in ["", "1", "2/2", "a/3", "1/0", "-1/2"] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
        assert_eq!(Shard::parse("2/3").unwrap(), Shard { index: 2, count: 3 });
    }
}
