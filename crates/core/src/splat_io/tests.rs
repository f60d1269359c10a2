use super::*;

/// One degree-1 Gaussian in ASCII, properties shuffled and with ones a reader must skip.
fn shuffled_degree_one() -> String {
    let mut names = vec![
        "nx", "rot_2", "f_dc_1", "scale_1", "y", "opacity", "x", "rot_0", "z", "f_dc_0", "scale_0",
        "rot_3", "f_dc_2", "ny", "rot_1", "scale_2", "nz",
    ]
    .into_iter()
    .map(String::from)
    .collect::<Vec<_>>();
    names.extend((0..9).rev().map(|i| format!("f_rest_{i}")));
    let value = |name: &str| -> f32 {
        match name {
            "x" => 1.0,
            "y" => 2.0,
            "z" => 3.0,
            "f_dc_0" => 0.1,
            "f_dc_1" => 0.2,
            "f_dc_2" => 0.3,
            "opacity" => -0.5,
            "scale_0" => -1.0,
            "scale_1" => -2.0,
            "scale_2" => -3.0,
            "rot_0" => 0.9,
            "rot_1" => 0.1,
            "rot_2" => 0.2,
            "rot_3" => 0.3,
            rest if rest.starts_with("f_rest_") => 10.0 + rest[7..].parse::<f32>().unwrap(),
            _ => 7.0,
        }
    };
    let mut text =
        "ply\nformat ascii 1.0\ncomment exported by a trainer\nelement vertex 1\n".to_string();
    names
        .iter()
        .for_each(|n| text += &format!("property float {n}\n"));
    text += "element camera 1\nproperty float fx\nend_header\n";
    text += &names
        .iter()
        .map(|n| value(n).to_string())
        .collect::<Vec<_>>()
        .join(" ");
    text + "\n500\n"
}

#[test]
fn reads_properties_in_any_order_and_skips_the_rest() {
    let cloud = parse_splat_ply(shuffled_degree_one().as_bytes()).unwrap();
    assert_eq!(cloud.means, vec![[1.0, 2.0, 3.0]]);
    assert_eq!(cloud.sh_degree, 1);
    assert_eq!(cloud.opacity_logits, vec![-0.5]);
    assert_eq!(cloud.log_scales, vec![[-1.0, -2.0, -3.0]]);
    assert_eq!(cloud.rotations, vec![[0.9, 0.1, 0.2, 0.3]]);
    // Channel-major: f_rest_0..2 are red's three degree-1 coefficients, 3..5 green's, 6..8 blue's.
    assert_eq!(
        cloud.sh_of(0),
        &[
            [0.1, 0.2, 0.3],
            [10.0, 13.0, 16.0],
            [11.0, 14.0, 17.0],
            [12.0, 15.0, 18.0]
        ]
    );
    assert!(is_splat_ply(shuffled_degree_one().as_bytes()));
}

fn cloud(degree: u32, count: usize) -> SplatCloud {
    let k = ((degree + 1) * (degree + 1)) as usize;
    SplatCloud {
        means: (0..count).map(|i| [i as f32, -(i as f32), 0.5]).collect(),
        sh_degree: degree,
        sh: (0..count * k)
            .map(|j| [j as f32, 0.5 * j as f32, -(j as f32)])
            .collect(),
        opacity_logits: (0..count).map(|i| i as f32 - 1.0).collect(),
        log_scales: (0..count).map(|i| [-(i as f32), -2.0, -3.0]).collect(),
        rotations: (0..count).map(|i| [1.0, i as f32, 0.0, 0.0]).collect(),
    }
}

#[test]
fn written_captures_read_back_exactly_for_every_degree() {
    for degree in 0..=3 {
        let written = cloud(degree, 5);
        let bytes = write_splat_ply(&written);
        assert!(is_splat_ply(&bytes));
        assert_eq!(parse_splat_ply(&bytes).unwrap(), written, "degree {degree}");
    }
}

#[test]
fn a_mesh_ply_is_not_a_capture() {
    let mesh = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n";
    assert!(!is_splat_ply(mesh.as_bytes()));
}

#[test]
fn bad_captures_name_the_property_or_gaussian() {
    let good = shuffled_degree_one();
    let missing = good.replace("property float scale_1\n", "");
    let missing = missing.replacen(" -2 ", " ", 1);
    let err = parse_splat_ply(missing.as_bytes()).unwrap_err();
    assert!(err.contains("'scale_1'"), "{err}");

    let mut nan = cloud(0, 3);
    nan.log_scales[2][1] = f32::NAN;
    let err = parse_splat_ply(&write_splat_ply(&nan)).unwrap_err();
    assert!(
        err.contains("Gaussian 2") && err.contains("'scale_1'"),
        "{err}"
    );

    let mut zero = cloud(0, 2);
    zero.rotations[1] = [0.0; 4];
    let err = parse_splat_ply(&write_splat_ply(&zero)).unwrap_err();
    assert!(err.contains("Gaussian 1") && err.contains("rot_0"), "{err}");

    let partial_sh = good.replace("property float f_rest_8\n", "");
    let err = parse_splat_ply(partial_sh.as_bytes()).unwrap_err();
    assert!(err.contains("8 'f_rest_*'"), "{err}");

    let huge = write_splat_ply(&cloud(0, 2));
    let text =
        String::from_utf8_lossy(&huge).replacen("element vertex 2", "element vertex 4000000000", 1);
    let err = parse_splat_ply(text.as_bytes()).unwrap_err();
    assert!(err.contains("vertex"), "{err}");
}
