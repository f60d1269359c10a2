//! What a rig's spec may hold where it is written: items that need a depth stream or a lens the
//! layout's calibration files cannot state are refused.

use rslam_core::Distortion;
use rslam_perturb::sensor::distortion;
use rslam_perturb::PerturbSpec;

use crate::{JobPart, PipelineError};

/// Where a rig is written, which decides what it can take.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RigLayout {
    /// The EuRoC layout: cameras without depth; sensor.yaml and ORB-SLAM3's settings describe
    /// radial-tangential lenses.
    Euroc,
    /// `rgbd-imu`: the TUM layout with `imu0/` beside it.
    RgbdImu,
}

/// Refuses what a rig cannot do: `misalign` where its cameras have no depth (EuRoC), and a
/// lens other than `distortion:radtan` on EuRoC rigs (any lens on `rgbd-imu`). Image and depth
/// corruptions apply to every camera or the one named (`cam1:fog:3`), the shutter (`exposure`,
/// `rolling_shutter`) and the lens to every camera, `rot`/`trans`/`fast` to the rig's motion
/// ([`body_path`]). Calibration items and the sensors named are checked against the rig by
/// [`PerturbedRig::new`].
pub fn check_rig_spec(spec: &PerturbSpec, layout: RigLayout) -> Result<(), PipelineError> {
    if let (Some(misalign), RigLayout::Euroc) = (spec.misalign, layout) {
        return Err(PipelineError::option(
            JobPart::Spec,
            format!("'misalign:{}': the rig's cameras have no depth stream to delay (for a time offset between sensors: cam_imu_offset)", misalign.frames),
        ));
    }
    let why = match (&spec.distortion, layout) {
        (None, _) | (Some(Distortion::Radtan { .. }), RigLayout::Euroc) => return Ok(()),
        (Some(_), RigLayout::Euroc) => "EuRoC's sensor.yaml and ORB-SLAM3's stereo settings written here describe radial-tangential lenses: use distortion:radtan(k1,k2,p1,p2)",
        (Some(_), RigLayout::RgbdImu) => "the rgbd-imu rig does not support a lens yet; the one-camera render and the EuRoC rigs (radtan) do",
    };
    let lens = spec
        .distortion
        .as_ref()
        .map(distortion::item)
        .unwrap_or_default();
    Err(PipelineError::option(
        JobPart::Spec,
        format!("'{lens}': {why}"),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::camera_frame_spec;

    #[test]
    fn misalign_needs_a_depth_stream_and_motion_items_are_the_rigs() {
        let spec = PerturbSpec::parse("fog:2,misalign:3").unwrap();
        let err = check_rig_spec(&spec, RigLayout::Euroc)
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("spec: 'misalign:3': the rig's cameras have no depth stream"),
            "{err}"
        );
        assert!(!err.contains('\n'), "{err}");
        check_rig_spec(&spec, RigLayout::RgbdImu).unwrap();
        let motion =
            PerturbSpec::parse("fog:2,rot:1,trans:0.01@smooth,fast:2,exposure:10").unwrap();
        check_rig_spec(&motion, RigLayout::Euroc).unwrap();
        let frame_spec = camera_frame_spec(&motion, "cam0");
        assert_eq!(frame_spec.fast, None, "the motion has taken fast already");
        assert_eq!(frame_spec.rotation, motion.rotation);
    }
}
