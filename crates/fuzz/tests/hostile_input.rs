//! Every parser, fed any bytes and any mutation of its seed files: `Ok` with a value that keeps
//! its invariants (no NaN pose, no index out of range, no name that leaves the output folder), or
//! a one-line error naming the file or flag; never a panic. The same targets as the fuzzer.

use proptest::collection::vec;
use proptest::prelude::*;
use rslam_fuzz::mutate::mutate;
use rslam_fuzz::{corpus, run_one, target, Outcome, Scratch, TARGETS};

/// Runs `input` through the target `name` in a fresh scratch folder; a finding fails the case.
fn survives(name: &str, input: &[u8]) -> Result<(), TestCaseError> {
    let target = target(name).expect("a target of that name");
    let dir = tempfile::tempdir().expect("scratch folder");
    (target.prepare)(dir.path()).expect("scratch files");
    let scratch = Scratch {
        dir: dir.path().to_path_buf(),
    };
    match run_one(target, &scratch, input) {
        Outcome::Found(finding) => Err(TestCaseError::fail(format!(
            "{}: {} (input {:?})",
            finding.kind,
            finding.message,
            String::from_utf8_lossy(input)
        ))),
        Outcome::Accepted | Outcome::Rejected(_) => Ok(()),
    }
}

/// A seed of `name` after the mutations `entropy` draws.
fn mutated_seed(name: &str, pick: usize, entropy: &[u8]) -> Vec<u8> {
    let seeds = corpus::seeds(name).expect("seed files");
    mutate(&seeds[pick % seeds.len()], &seeds, entropy)
}

macro_rules! hostile_input_properties {
    ($($name:ident),* $(,)?) => {
        /// The targets with properties below, to check that none is left out.
        const COVERED: &[&str] = &[$(stringify!($name)),*];
        $(
            mod $name {
                use super::*;

                proptest! {
                    #![proptest_config(ProptestConfig {
                        failure_persistence: None,
                        ..ProptestConfig::default()
                    })]

                    #[test]
                    fn any_bytes(input in vec(any::<u8>(), 0..512)) {
                        survives(stringify!($name), &input)?;
                    }

                    #[test]
                    fn any_mutation_of_a_seed(pick in any::<usize>(), entropy in vec(any::<u8>(), 8..160)) {
                        survives(stringify!($name), &mutated_seed(stringify!($name), pick, &entropy))?;
                    }
                }

                #[test]
                fn every_seed_is_accepted() {
                    let target = target(stringify!($name)).unwrap();
                    let dir = tempfile::tempdir().unwrap();
                    (target.prepare)(dir.path()).unwrap();
                    let scratch = Scratch { dir: dir.path().to_path_buf() };
                    for (i, seed) in corpus::seeds(stringify!($name)).unwrap().iter().enumerate() {
                        assert_eq!(run_one(target, &scratch, seed), Outcome::Accepted, "seed {i}");
                    }
                }
            }
        )*
    };
}

hostile_input_properties!(
    spec,
    camera,
    shard,
    trajectory,
    ply,
    splat_ply,
    obj,
    mtl,
    gltf,
    glb,
    associations,
    rgb_list,
    cam_params,
    manifest,
    checksums,
    image,
    depth_png,
    euroc_camera_yaml,
    euroc_camera_csv,
    euroc_imu_yaml,
    euroc_imu,
    euroc_groundtruth,
    tum_vi_camchain,
    tum_vi_imu_config,
    ros2_bag,
    suite,
    method,
);

#[test]
fn every_target_has_its_properties() {
    let names: Vec<&str> = TARGETS.iter().map(|t| t.name).collect();
    assert_eq!(names, COVERED);
}
