//! The IMU items of a `--perturb` spec and their one-line descriptions for `rslam list`.
//!
//! ```text
//! imu_noise:K                    noise densities and random walks × K
//! imu_bias_step:GYRO/ACC         a bias step of GYRO rad/s and ACC m/s² at a random time
//! imu_saturation:GYRO/ACC        readings clipped at ±GYRO rad/s and ±ACC m/s² per axis
//! imu_drop:P | imu_drop:P/L      samples dropped with probability P (in bursts of mean length L)
//! imu_jitter:MS                  timestamp jitter of standard deviation MS
//! cam_imu_offset:MS              camera timestamps shifted by MS against the IMU's
//! ```
//!
//! Two-valued items separate their values with `/`: a comma separates items.

use serde::{Deserialize, Serialize};

use crate::applies::{ItemEntry, Need};

pub const NOISE: &str = "imu_noise";
pub const BIAS_STEP: &str = "imu_bias_step";
pub const SATURATION: &str = "imu_saturation";
pub const DROP: &str = "imu_drop";
pub const JITTER: &str = "imu_jitter";
pub const CAM_IMU_OFFSET: &str = "cam_imu_offset";

/// A value for the gyroscope (rad/s) and one for the accelerometer (m/s²).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PerSensor {
    pub gyroscope: f64,
    pub accelerometer: f64,
}

/// `imu_drop:P[/L]`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SampleDrop {
    /// The fraction of samples dropped, in [0, 1).
    pub probability: f64,
    /// Mean length of a burst of dropped samples; `None`: each sample dropped independently.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub burst: Option<f64>,
}

/// The IMU items of a spec; each at most once, applied in the physical order of the fields
/// (the sensor's errors, its range, the transport, the time stamping), whatever the written
/// order.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ImuSpec {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub noise_scale: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bias_step: Option<PerSensor>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub saturation: Option<PerSensor>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drop: Option<SampleDrop>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub jitter_ms: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cam_imu_offset_ms: Option<f64>,
}

pub static IMU_ITEMS: &[ItemEntry] = &[
    ItemEntry {
        name: NOISE,
        syntax: "imu_noise:K",
        description: "IMU noise densities and bias random walks × K (Kalibr's model, per axis). Rendered: the IMU is synthesised with them (any K ≥ 0); recorded: independent noise of (K² − 1)× imu0/sensor.yaml's variances is added (K ≥ 1), and its bias walk goes into the ground-truth biases; sensor.yaml keeps the nominal values. A ROS 2 bag: (K² − 1)× the white noise its Imu covariances state, no bias walk",
        needs: &[Need::Imu],
    },
    ItemEntry {
        name: BIAS_STEP,
        syntax: "imu_bias_step:GYRO/ACC",
        description: "the gyroscope and accelerometer biases jump by GYRO rad/s and ACC m/s² (each a random direction) at a time uniform in the middle 80 % of the IMU's span; readings and ground-truth biases from then on; manifest: time and step vectors",
        needs: &[Need::Imu],
    },
    ItemEntry {
        name: SATURATION,
        syntax: "imu_saturation:GYRO/ACC",
        description: "each reading clipped per axis to ±GYRO rad/s and ±ACC m/s², as a sensor at the end of its range; manifest: samples clipped",
        needs: &[Need::Imu],
    },
    ItemEntry {
        name: DROP,
        syntax: "imu_drop:P | imu_drop:P/L",
        description: "IMU samples dropped, a fraction P of them: each independently, or in bursts of mean length L samples (two-state Markov chain); ground truth stays whole; manifest: samples dropped, longest gap",
        needs: &[Need::Imu],
    },
    ItemEntry {
        name: JITTER,
        syntax: "imu_jitter:MS",
        description: "IMU timestamps (not the readings) moved by N(0, MS ms), clipped to less than half the gap to either neighbour so that they stay strictly increasing (the std falls short of MS once MS nears a sixth of the sample period); manifest: realised std, draws clipped",
        needs: &[Need::Imu],
    },
    ItemEntry {
        name: CAM_IMU_OFFSET,
        syntax: "cam_imu_offset:MS",
        description: "every camera timestamp (data.csv and file name) + MS ms against the IMU's (negative allowed; Kalibr's timeshift_cam_imu = −MS); IMU and ground truth keep the body's clock; calibration files say 0",
        needs: &[Need::Imu, Need::NewStamps],
    },
];

/// Whether `name` is an IMU item.
pub fn is_imu_item(name: &str) -> bool {
    IMU_ITEMS.iter().any(|e| e.name == name)
}

/// The number `text`, part of the item's `value` (which the error quotes), if `ok` takes it.
fn number(
    text: &str,
    value: &str,
    what: &str,
    example: &str,
    ok: impl Fn(f64) -> bool,
) -> Result<f64, String> {
    text.trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && ok(*v))
        .ok_or_else(|| format!("'{value}': expected {what}, e.g. {example}"))
}

/// `GYRO/ACC`, both positive.
fn per_sensor(value: &str, example: &str) -> Result<PerSensor, String> {
    let what = "GYRO/ACC: rad/s and m/s², both > 0";
    let (g, a) = value
        .split_once('/')
        .ok_or_else(|| format!("'{value}': expected {what}, e.g. {example}"))?;
    let positive = |text: &str| number(text, value, what, example, |v| v > 0.0);
    Ok(PerSensor {
        gyroscope: positive(g)?,
        accelerometer: positive(a)?,
    })
}

fn sample_drop(value: &str) -> Result<SampleDrop, String> {
    let example = "imu_drop:0.01 or imu_drop:0.01/20";
    let (p, burst) = match value.split_once('/') {
        Some((p, l)) => (p, Some(l)),
        None => (value, None),
    };
    let probability = number(p, value, "a probability P in [0, 1)", example, |v| {
        (0.0..1.0).contains(&v)
    })?;
    let burst = burst
        .map(|l| {
            number(
                l,
                value,
                "a mean burst length L ≥ 1 samples",
                example,
                |v| v >= 1.0,
            )
        })
        .transpose()?;
    if let Some(l) = burst {
        // The chain enters a burst with probability P / (L (1 − P)) per sample.
        if probability > l / (l + 1.0) {
            return Err(format!(
                "'{value}': a fraction {probability} in bursts of mean length {l} needs P ≤ L/(L+1) = {}",
                l / (l + 1.0)
            ));
        }
    }
    Ok(SampleDrop { probability, burst })
}

impl ImuSpec {
    /// Takes the IMU item `name` (one of [`IMU_ITEMS`]) with its value; the error says what was
    /// expected.
    pub fn add(&mut self, name: &str, value: &str, mode: Option<&str>) -> Result<(), String> {
        if let Some(m) = mode {
            return Err(format!("{name} takes no mode, got '@{m}'"));
        }
        match name {
            NOISE => {
                self.noise_scale = Some(number(
                    value,
                    value,
                    "a scale K ≥ 0",
                    "imu_noise:3",
                    |v| v >= 0.0,
                )?)
            }
            BIAS_STEP => self.bias_step = Some(per_sensor(value, "imu_bias_step:0.01/0.1")?),
            SATURATION => self.saturation = Some(per_sensor(value, "imu_saturation:2/40")?),
            DROP => self.drop = Some(sample_drop(value)?),
            JITTER => {
                self.jitter_ms = Some(number(
                    value,
                    value,
                    "a standard deviation in milliseconds ≥ 0",
                    "imu_jitter:0.5",
                    |v| v >= 0.0,
                )?)
            }
            CAM_IMU_OFFSET => {
                self.cam_imu_offset_ms = Some(number(
                    value,
                    value,
                    "an offset in milliseconds (negative allowed)",
                    "cam_imu_offset:5",
                    |_| true,
                )?)
            }
            other => return Err(format!("'{other}' is not an IMU item")),
        }
        Ok(())
    }

    pub fn is_empty(&self) -> bool {
        *self == Self::default()
    }

    /// The items as written canonically, in the order applied.
    pub fn items(&self) -> Vec<String> {
        let pair = |p: PerSensor| format!("{}/{}", p.gyroscope, p.accelerometer);
        let drop = |d: SampleDrop| match d.burst {
            Some(l) => format!("{}/{l}", d.probability),
            None => d.probability.to_string(),
        };
        [
            self.noise_scale.map(|k| format!("{NOISE}:{k}")),
            self.bias_step.map(|p| format!("{BIAS_STEP}:{}", pair(p))),
            self.saturation.map(|p| format!("{SATURATION}:{}", pair(p))),
            self.drop.map(|d| format!("{DROP}:{}", drop(d))),
            self.jitter_ms.map(|ms| format!("{JITTER}:{ms}")),
            self.cam_imu_offset_ms
                .map(|ms| format!("{CAM_IMU_OFFSET}:{ms}")),
        ]
        .into_iter()
        .flatten()
        .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parsed(items: &[(&str, &str)]) -> Result<ImuSpec, String> {
        let mut spec = ImuSpec::default();
        for (name, value) in items {
            spec.add(name, value, None)?;
        }
        Ok(spec)
    }

    #[test]
    fn every_item_parses_and_prints_back() {
        let items = [
            (NOISE, "2.5"),
            (BIAS_STEP, "0.01/0.2"),
            (SATURATION, "4/39.2"),
            (DROP, "0.05/3"),
            (JITTER, "0.25"),
            (CAM_IMU_OFFSET, "-7.5"),
        ];
        let spec = parsed(&items).unwrap();
        let written: Vec<String> = items.iter().map(|(n, v)| format!("{n}:{v}")).collect();
        assert_eq!(spec.items(), written);
        assert_eq!(
            spec.bias_step,
            Some(PerSensor {
                gyroscope: 0.01,
                accelerometer: 0.2
            })
        );
        assert_eq!(
            parsed(&[(DROP, "0.1")]).unwrap().drop,
            Some(SampleDrop {
                probability: 0.1,
                burst: None
            })
        );
        assert!(ImuSpec::default().is_empty() && !spec.is_empty());
    }

    #[test]
    fn bad_values_say_what_was_expected() {
        for (name, value, expected) in [
            (NOISE, "-1", "a scale K ≥ 0"),
            (NOISE, "nan", "a scale K ≥ 0"),
            (BIAS_STEP, "0.01", "GYRO/ACC"),
            (BIAS_STEP, "0.01/x", "GYRO/ACC"),
            (SATURATION, "0/10", "both > 0"),
            (SATURATION, "inf/10", "both > 0"),
            (DROP, "1", "a probability P in [0, 1)"),
            (DROP, "0.1/0.5", "a mean burst length L ≥ 1"),
            (DROP, "0.6/1", "needs P ≤ L/(L+1)"),
            (JITTER, "-0.1", "milliseconds ≥ 0"),
            (CAM_IMU_OFFSET, "five", "an offset in milliseconds"),
        ] {
            let err = parsed(&[(name, value)]).unwrap_err();
            assert!(err.contains(expected), "{name}:{value}: {err}");
            assert!(err.contains(value), "{name}:{value}: {err}");
        }
        let err = ImuSpec::default()
            .add(JITTER, "1", Some("dynamic"))
            .unwrap_err();
        assert_eq!(err, "imu_jitter takes no mode, got '@dynamic'");
    }
}
