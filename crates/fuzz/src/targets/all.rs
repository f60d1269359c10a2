//! Every fuzz target, in the order `rslam-fuzz` runs them.

use super::{dataset, euroc, mesh, ros2_bag, suite, text, trajectory, tum_vi};
use crate::target::{nothing, Target};

pub static TARGETS: &[Target] = &[
    Target {
        name: "spec",
        file: None,
        prepare: nothing,
        check: text::spec,
    },
    Target {
        name: "camera",
        file: None,
        prepare: nothing,
        check: text::camera,
    },
    Target {
        name: "shard",
        file: None,
        prepare: nothing,
        check: text::shard,
    },
    Target {
        name: "trajectory",
        file: Some(trajectory::FILE),
        prepare: nothing,
        check: trajectory::check,
    },
    Target {
        name: "ply",
        file: Some(mesh::PLY),
        prepare: nothing,
        check: mesh::ply,
    },
    Target {
        name: "splat_ply",
        file: Some(mesh::CAPTURE),
        prepare: nothing,
        check: mesh::capture,
    },
    Target {
        name: "obj",
        file: Some(mesh::OBJ),
        prepare: mesh::prepare_obj,
        check: mesh::obj,
    },
    Target {
        name: "mtl",
        file: Some(mesh::MTL),
        prepare: mesh::prepare_mtl,
        check: mesh::mtl,
    },
    Target {
        name: "gltf",
        file: Some(mesh::GLTF),
        prepare: nothing,
        check: mesh::gltf,
    },
    Target {
        name: "glb",
        file: Some(mesh::GLB),
        prepare: nothing,
        check: mesh::glb,
    },
    Target {
        name: "associations",
        file: Some(dataset::ASSOCIATIONS),
        prepare: dataset::prepare_tum,
        check: dataset::associations,
    },
    Target {
        name: "rgb_list",
        file: Some(dataset::RGB_LIST),
        prepare: dataset::prepare_tum,
        check: dataset::rgb_list,
    },
    Target {
        name: "cam_params",
        file: Some(dataset::CAM_PARAMS),
        prepare: dataset::prepare_replica,
        check: dataset::cam_params,
    },
    Target {
        name: "manifest",
        file: Some(dataset::MANIFEST),
        prepare: dataset::prepare_replica,
        check: dataset::manifest,
    },
    Target {
        name: "checksums",
        file: Some(dataset::CHECKSUMS),
        prepare: nothing,
        check: dataset::checksums,
    },
    Target {
        name: "image",
        file: Some(dataset::IMAGE),
        prepare: nothing,
        check: dataset::image,
    },
    Target {
        name: "depth_png",
        file: Some(dataset::DEPTH_PNG),
        prepare: nothing,
        check: dataset::depth_png,
    },
    Target {
        name: "euroc_camera_yaml",
        file: Some(euroc::CAMERA_YAML),
        prepare: euroc::prepare,
        check: euroc::camera_yaml,
    },
    Target {
        name: "euroc_camera_csv",
        file: Some(euroc::CAMERA_CSV),
        prepare: euroc::prepare,
        check: euroc::camera_csv,
    },
    Target {
        name: "euroc_imu_yaml",
        file: Some(euroc::IMU_YAML),
        prepare: euroc::prepare,
        check: euroc::imu_yaml,
    },
    Target {
        name: "euroc_imu",
        file: Some(euroc::IMU_CSV),
        prepare: euroc::prepare,
        check: euroc::imu,
    },
    Target {
        name: "euroc_groundtruth",
        file: Some(euroc::GROUND_TRUTH_CSV),
        prepare: euroc::prepare,
        check: euroc::ground_truth,
    },
    Target {
        name: "tum_vi_camchain",
        file: Some(tum_vi::CAMCHAIN),
        prepare: tum_vi::prepare,
        check: tum_vi::camchain,
    },
    Target {
        name: "tum_vi_imu_config",
        file: Some(tum_vi::IMU_CONFIG),
        prepare: tum_vi::prepare,
        check: tum_vi::imu_config,
    },
    Target {
        name: "ros2_bag",
        file: Some(ros2_bag::STORAGE),
        prepare: ros2_bag::prepare,
        check: ros2_bag::storage,
    },
    Target {
        name: "suite",
        file: Some(suite::SUITE),
        prepare: suite::prepare_suite,
        check: suite::suite,
    },
    Target {
        name: "method",
        file: Some(suite::METHOD),
        prepare: nothing,
        check: suite::method,
    },
];
